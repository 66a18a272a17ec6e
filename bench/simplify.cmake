# Simplifier benchmarks (tandem part, working surface): quality against full resolution over E0
# and alpha, and extraction + simplification throughput (tandem against brute force).
add_executable(bench_simplify_quality ${CMAKE_CURRENT_SOURCE_DIR}/simplify_quality.cpp)
target_link_libraries(bench_simplify_quality PRIVATE geotandem::tandem geotandem::mesh)
geotandem_target_defaults(bench_simplify_quality)
add_executable(bench_simplify_throughput ${CMAKE_CURRENT_SOURCE_DIR}/simplify_throughput.cpp)
target_link_libraries(bench_simplify_throughput PRIVATE geotandem::tandem geotandem::mesh geotandem::workflow
                                                        geotandem::builtin)
# The seismic field is the quickstart recipe's attribute, read from the source tree at run time.
target_compile_definitions(bench_simplify_throughput
                           PRIVATE GEOTANDEM_QUICKSTART_RECIPE="${PROJECT_SOURCE_DIR}/workflows/quickstart.yaml")
geotandem_target_defaults(bench_simplify_throughput)
