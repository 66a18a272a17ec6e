# bench_runtime_speedup: 1 and 2 local workers against the in-process block route on an analytic
# cube (speed-up, bytes per merge, peak RSS of workers and manager, manager CPU share). Run it as
#   build/release/bin/bench_runtime_speedup build/release/bin/geotandem 256 64 1,2
add_executable(bench_runtime_speedup ${CMAKE_CURRENT_SOURCE_DIR}/runtime_speedup.cpp)
target_link_libraries(bench_runtime_speedup PRIVATE geotandem::runtime geotandem::synth geotandem::store)
geotandem_target_defaults(bench_runtime_speedup)
add_dependencies(bench_runtime_speedup geotandem)

# bench_surface_route: a partial surface from worker to worker, directly or through the manager
# (store and forward, as the runtime does), with the runtime's messages over TCP; time per surface
# and CPU of each process. Run it as
#   build/release/bin/bench_surface_route 1,4,16 16
add_executable(bench_surface_route ${CMAKE_CURRENT_SOURCE_DIR}/surface_route.cpp)
target_link_libraries(bench_surface_route PRIVATE geotandem::runtime cppzmq)
geotandem_target_defaults(bench_surface_route)

# bench_manager_cost: the manager's own cost per message and per task (real Manager, CURVE socket,
# schedule, relay, index writer) with workers that answer at once (issue 55, part 3). Run it as
#   build/release/bin/bench_manager_cost 256,256,64 8 2,8,64 1
add_executable(bench_manager_cost ${CMAKE_CURRENT_SOURCE_DIR}/manager_cost.cpp)
target_link_libraries(bench_manager_cost PRIVATE geotandem::runtime geotandem::store cppzmq)
target_include_directories(bench_manager_cost PRIVATE ${PROJECT_SOURCE_DIR}/framework/store/src)
geotandem_target_defaults(bench_manager_cost)

# bench_scale_model: a run's task log replayed through the real Schedule with 1 to 1024 simulated
# workers (issue 55, part 4). Run it as
#   build/release/bin/bench_scale_model OUT/store/task-log.tsv [1,2,...,1024] [cube X,Y,Z] [leaf] [run] [cores]
add_executable(bench_scale_model ${CMAKE_CURRENT_SOURCE_DIR}/scale_model.cpp)
target_link_libraries(bench_scale_model PRIVATE geotandem::runtime)
geotandem_target_defaults(bench_scale_model)
