# bench_label_cube: the label cube (issue 54) written at n^3 (default 1024) against the extraction's
# own time on the same analytic cube, with the peak memory of each phase.
add_executable(bench_label_cube ${CMAKE_CURRENT_SOURCE_DIR}/workflow/label_cube_bench.cpp)
target_link_libraries(bench_label_cube PRIVATE geotandem::workflow geotandem::synth geotandem::store)
geotandem_target_defaults(bench_label_cube)
