# bench_volume_io: SEG-Y and raw write throughput and box reads (whole cube, 64^3 blocks, slices).
add_executable(bench_volume_io ${CMAKE_CURRENT_SOURCE_DIR}/volume_io.cpp)
target_link_libraries(bench_volume_io PRIVATE geotandem::volume)
geotandem_target_defaults(bench_volume_io)
