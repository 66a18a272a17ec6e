# bench_store: component store throughput: durable commits by batch size, record reads, index
# queries over 100 000 rows, exports per format.
add_executable(bench_store ${CMAKE_CURRENT_SOURCE_DIR}/store/store_bench.cpp)
target_link_libraries(bench_store PRIVATE geotandem::store geotandem::mesh)
geotandem_target_defaults(bench_store)

# bench_store_check: `store check` (every record read back and verified) on 100 000 components.
add_executable(bench_store_check ${CMAKE_CURRENT_SOURCE_DIR}/store/check_bench.cpp)
target_link_libraries(bench_store_check PRIVATE geotandem::store geotandem::mesh)
geotandem_target_defaults(bench_store_check)
