# bench_mc_throughput: marching-cubes cells/s and triangles/s on one core (blobs + noise, smooth, empty).
add_executable(bench_mc_throughput ${CMAKE_CURRENT_SOURCE_DIR}/mc_throughput.cpp)
target_link_libraries(bench_mc_throughput PRIVATE geotandem::tandem)
geotandem_target_defaults(bench_mc_throughput)
