# bench_box_read: box reads versus sequential reads of chunked netCDF-4 and Zarr cubes (GDAL).
add_executable(bench_box_read ${CMAKE_CURRENT_SOURCE_DIR}/box_read.cpp)
target_link_libraries(bench_box_read PRIVATE geotandem::volume)
target_compile_definitions(bench_box_read PRIVATE GEOTANDEM_BENCH_DATA="${PROJECT_SOURCE_DIR}/build/bench-data")
geotandem_target_defaults(bench_box_read)

# bench_netcdf_slices: a cube rewritten in whole inline slices (bench/paper_cube.sh --netcdf-slices).
add_executable(bench_netcdf_slices ${CMAKE_CURRENT_SOURCE_DIR}/netcdf_slices.cpp)
target_link_libraries(bench_netcdf_slices PRIVATE geotandem::volume GDAL::GDAL)
geotandem_target_defaults(bench_netcdf_slices)
