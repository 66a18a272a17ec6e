# bench_scheduler_latency: time from submit() to a job running, and to its first line of output,
# on the local backend and on Slurm (needs SLURM_CONF: see scripts/slurm-bench.sh).
add_executable(bench_scheduler_latency ${CMAKE_CURRENT_SOURCE_DIR}/schedulers/scheduler_latency.cpp)
target_link_libraries(bench_scheduler_latency PRIVATE geotandem::schedulers)
geotandem_target_defaults(bench_scheduler_latency)
