# Mesh part: topology check, split, measures and distances on ~1 M triangles.
add_executable(mesh_bench ${CMAKE_CURRENT_SOURCE_DIR}/mesh/mesh_bench.cpp)
target_link_libraries(mesh_bench PRIVATE geotandem::mesh)
geotandem_target_defaults(mesh_bench)
