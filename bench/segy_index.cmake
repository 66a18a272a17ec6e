# bench_segy_index: opening an unsorted SEG-Y file of 1 M traces through the trace index (issue 54).
add_executable(bench_segy_index ${CMAKE_CURRENT_SOURCE_DIR}/segy_index.cpp)
target_link_libraries(bench_segy_index PRIVATE geotandem::volume)
geotandem_target_defaults(bench_segy_index)
