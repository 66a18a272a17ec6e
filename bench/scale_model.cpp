// bench_scale_model: a real run's task log (STORE/task-log.tsv, written by every run with workers)
// replayed through the real Schedule with N simulated workers (geotandem/runtime/scale_model.hpp
// states the model's assumptions). Prints, per worker count, the predicted wall time, the
// efficiency (predicted 1-worker time / (N x predicted time)), the manager's and the index
// writer's busy shares, the tail after the last EXTRACT (the merges near the root) and what
// saturates first.
//   bench_scale_model TASK_LOG [workers=1,2,4,...,1024] [cube=X,Y,Z (cells; default the recorded)]
//                     [leaf=L (default the recorded)] [run=K (default the last that ended)]
//                     [cores=C (default the recorded host's, its other load included; 0: a core per
//                     worker and no other load, as on a cluster)]
// For the lead's three-node run: bench_scale_model OUT/store/task-log.tsv 8
#include <cmath>
#include <cstdio>

#include "bench_args.hpp"
#include "geotandem/runtime/scale_model.hpp"

using namespace geotandem;

int bench_main(int argc, char** argv) {
  const bench::Args args(argc, argv,
                         "bench_scale_model TASK_LOG [workers=1,2,4,...,1024] [cube=X,Y,Z] [leaf=L] [run=K] [cores=C]");
  if (args.size() < 1) args.fail(1, "is missing: the task log of a run (STORE/task-log.tsv)");
  const std::vector<runtime::TaskLogRun> runs = runtime::read_task_log(args.text(1, ""));
  const std::vector<std::int64_t> counts = args.integers(2, "1,2,4,8,16,32,56,64,128,256,512,1024", 1);
  std::size_t pick = runs.size();
  for (std::size_t i = runs.size(); i-- > 0;)
    if (runs[i].wall_seconds > 0) {
      pick = i;
      break;
    }
  if (args.has(5)) pick = static_cast<std::size_t>(args.integer(5, 0, 0));
  if (pick >= runs.size()) throw std::runtime_error("the task log holds no run that ended");
  const runtime::TaskLogRun& run = runs[pick];
  const runtime::ScaleModelCalibration c = runtime::calibrate(run);
  volume::Box cube = run.cube;
  if (args.has(3)) {
    const std::vector<std::int64_t> shape = args.integers(3, "", 1);
    if (shape.size() != 3) args.fail(3, "is not three sizes X,Y,Z");
    cube = volume::Box{{0, 0, 0}, {shape[0], shape[1], shape[2]}};
  }
  const std::int64_t leaf = args.has(4) ? args.integer(4, 0, 1) : run.leaf_size;
  const tandem::BlockTree tree(cube, leaf);
  const std::size_t cores = args.has(6) ? static_cast<std::size_t>(args.integer(6, 0, 0)) : c.cores;
  std::printf("recorded run %zu: cube %s, leaves of %lld, %zu tasks, %llu worker(s), %.2f s wall, manager CPU "
              "%.2f s\n",
              pick, run.cube.to_string().c_str(), static_cast<long long>(run.leaf_size), run.tasks.size(),
              static_cast<unsigned long long>(c.recorded_workers), c.recorded_wall, c.recorded_manager_cpu);
  std::printf("calibration: EXTRACT mean %.2f ms; surface bytes = %.3g x leaves^%.3f; MERGE %.2f ms + %.3g ms/MiB; "
              "SEND %.2f ms + %.3g ms/MiB; final pass %.2f s over %llu leaves; manager %.1f us/message; index "
              "writer %.1f us/leaf; worker start %.2f s; per task overhead %.2f ms (EXTRACT), gap %.2f ms\n",
              1e3 * c.extract_mean, c.bytes_k, c.bytes_p, 1e3 * c.merge_fixed, 1e3 * c.merge_per_byte * 1048576.0,
              1e3 * c.send_fixed, 1e3 * c.send_per_byte * 1048576.0, c.finish_seconds,
              static_cast<unsigned long long>(c.finish_leaves), 1e6 * c.manager_per_message, 1e6 * c.index_per_row,
              c.startup, 1e3 * c.overhead_extract, 1e3 * c.gap);
  std::printf("processors: recorded on %zu cores, a worker's share of a core %.2f, the manager's %.2f, other load "
              "%.2f runnable; replayed on %s; batches of up to %zu leaves; empty surfaces %s\n",
              c.cores, c.cpu_share, c.manager_share, c.background,
              cores ? (std::to_string(cores) + " cores with that load").c_str() : "a core per worker, no other load",
              c.batch, c.drops ? "dropped" : "sent (an older log)");
  std::printf("predicted for cube %s, leaves of %lld (%zu leaves):\n", cube.to_string().c_str(),
              static_cast<long long>(leaf), tree.leaves().size());
  std::printf("%8s %11s %10s %9s %9s %9s %9s %8s %8s  %s\n", "workers", "wall_s", "efficiency", "manager", "index",
              "tail_s", "msg_wait", "sends", "merges", "saturates first");
  const double one = runtime::predict(c, tree, 1, cores).wall;
  for (const std::int64_t n : counts) {
    runtime::ScalePrediction p = runtime::predict(c, tree, static_cast<std::size_t>(n), cores);
    p.efficiency = one / (static_cast<double>(n) * p.wall);
    std::printf("%8lld %11.2f %9.0f%% %8.1f%% %8.1f%% %9.2f %7.2fms %8llu %8llu  %s\n", static_cast<long long>(n),
                p.wall, 100 * p.efficiency, 100 * p.manager_busy, 100 * p.index_busy, p.tail, 1e3 * p.manager_wait,
                static_cast<unsigned long long>(p.send), static_cast<unsigned long long>(p.merge), p.saturates.c_str());
    std::fflush(stdout);
  }
  return 0;
}

int main(int argc, char** argv) {
  return geotandem::bench::guarded_main("bench_scale_model", [&] { return bench_main(argc, argv); });
}
