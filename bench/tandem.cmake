# bench_mc_throughput: marching-cubes cells/s and triangles/s on one core (blobs + noise, smooth, empty).
add_executable(bench_mc_throughput ${CMAKE_CURRENT_SOURCE_DIR}/mc_throughput.cpp)
target_link_libraries(bench_mc_throughput PRIVATE geotandem::tandem)
geotandem_target_defaults(bench_mc_throughput)
# bench_tandem_memory: peak RSS and triangles held per layer, brute force against the tandem with
# and without dumping, each in a forked child, on a procedural analytic cube (default 512^3);
# writes an SVG plot (--svg).
add_executable(bench_tandem_memory ${CMAKE_CURRENT_SOURCE_DIR}/tandem_memory.cpp)
target_link_libraries(bench_tandem_memory PRIVATE geotandem::tandem geotandem::synth geotandem::mesh)
geotandem_target_defaults(bench_tandem_memory)
# bench_tandem_quality: anisotropy, distances to full resolution and small angles against alpha;
# writes an SVG plot (--svg).
add_executable(bench_tandem_quality ${CMAKE_CURRENT_SOURCE_DIR}/tandem_quality.cpp)
target_link_libraries(bench_tandem_quality PRIVATE geotandem::tandem geotandem::synth geotandem::mesh)
geotandem_target_defaults(bench_tandem_quality)
