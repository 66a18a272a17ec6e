# Attribute throughput, whole cube against fused block by block (plugins/attributes).
add_executable(bench_attributes ${CMAKE_CURRENT_SOURCE_DIR}/attributes_throughput.cpp)
target_link_libraries(bench_attributes PRIVATE geotandem::attributes)
geotandem_target_defaults(bench_attributes)
