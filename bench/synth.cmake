# Benchmarks of the synth part (included by bench/CMakeLists.txt).
add_executable(bench_synth_throughput ${CMAKE_CURRENT_SOURCE_DIR}/synth_throughput.cpp)
target_link_libraries(bench_synth_throughput PRIVATE geotandem::synth)
geotandem_target_defaults(bench_synth_throughput)
