# bench_runtime_speedup: 1 and 2 local workers against the in-process block route on an analytic
# cube (speed-up, bytes per merge, peak RSS of workers and manager, manager CPU share). Run it as
#   build/release/bin/bench_runtime_speedup build/release/bin/geotandem 256 64 1,2
add_executable(bench_runtime_speedup ${CMAKE_CURRENT_SOURCE_DIR}/runtime_speedup.cpp)
target_link_libraries(bench_runtime_speedup PRIVATE geotandem::runtime geotandem::synth geotandem::store)
geotandem_target_defaults(bench_runtime_speedup)
add_dependencies(bench_runtime_speedup geotandem)
