// bench_manager_cost: the manager's own cost (issue 55, part 3). The real Manager, its real ROUTER
// socket with CURVE, its Schedule, relay, task log and index writer, fed by W in-process workers
// that speak the protocol and do no work: an EXTRACT is answered at once (with `rows` index rows
// in a COMMIT), a SEND with a surface of `surface` bytes, a MERGE by taking the chunks in. What
// the manager then spends is its cost alone: CPU per message and per task, the messages per second
// it sustains (messages / its CPU), the index rows per second its writer commits, and so how many
// workers it can feed when a task takes a worker T seconds (T / manager CPU per task).
//   bench_manager_cost [cube=256,256,64] [leaf=8] [workers=2,8,64] [rows=1] [surface=4096]
// Prints one line per worker count. Not a test: figures only.
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <thread>
#include <zmq.hpp>

#include "../framework/runtime/src/worker_link.hpp"
#include "../framework/store/src/record.hpp"
#include "bench_args.hpp"
#include "geotandem/core/log.hpp"
#include "geotandem/core/progress.hpp"
#include "geotandem/runtime/manager.hpp"
#include "geotandem/runtime/surface_chunks.hpp"
#include "geotandem/volume/geometry.hpp"

using namespace geotandem;
using namespace std::chrono_literals;
namespace fs = std::filesystem;

namespace {

// A worker of the run that answers every task at once.
void idle_worker(const std::string& endpoint, const std::string& token, std::size_t rows, std::size_t surface_bytes,
                 std::atomic<std::uint64_t>& next_key) {
  zmq::context_t context(1);
  CancelToken cancel;
  runtime::detail::WorkerLink link(context, {.endpoint = endpoint, .token = token}, cancel);
  runtime::Message hello;
  hello.kind = runtime::MessageKind::hello;
  hello.text = token;
  hello.number = static_cast<std::uint64_t>(getpid());
  link.send(hello);
  const std::vector<std::byte> surface(surface_bytes, std::byte{7});
  store::RecordLocation where;
  where.shard = token;
  where.vertex_count = 4;
  where.triangle_count = 4;
  where.length = *store::detail::record_length(4, 4);
  const auto ask = [&] {
    runtime::Message m;
    m.kind = runtime::MessageKind::ask;
    link.send(m);
  };
  const auto done = [&](const runtime::Message& task, bool final) {
    runtime::Message d;
    d.kind = runtime::MessageKind::done;
    d.lease = task.lease;
    d.box[1] = final ? 1 : 0;
    link.send(d);
  };
  for (;;) {
    const std::optional<runtime::Message> m = link.receive(200ms);
    if (!m) continue;
    switch (m->kind) {
    case runtime::MessageKind::setup: break;
    case runtime::MessageKind::extract: {
      if (rows > 0) {
        runtime::Message c;
        c.kind = runtime::MessageKind::commit;
        c.lease = m->lease;
        for (std::size_t i = 0; i < rows; ++i) {
          store::IndexEntry e;
          e.key = next_key.fetch_add(1);
          e.location = where;
          e.stats.vertex_count = 4;
          e.stats.triangle_count = 4;
          c.entries.push_back(e);
        }
        link.send(c);
      }
      done(*m, false);
      break;
    }
    case runtime::MessageKind::send: {
      runtime::Message c;
      c.kind = runtime::MessageKind::surface_chunk;
      c.lease = m->lease;
      c.box[0] = static_cast<std::int64_t>(surface.size());
      c.bytes = surface;
      link.send(c);
      runtime::Message end;
      end.kind = runtime::MessageKind::surface;
      end.lease = m->lease;
      end.number = surface.size();
      end.box[0] = static_cast<std::int64_t>(runtime::surface_checksum(surface));
      link.send(end);
      break;
    }
    case runtime::MessageKind::merge: {
      std::uint64_t got = 0;
      while (got < m->number) {
        const std::optional<runtime::Message> c = link.receive(200ms);
        if (!c) continue;
        if (c->kind == runtime::MessageKind::finished) return;
        if (c->kind != runtime::MessageKind::merge_chunk) continue;
        got += c->bytes.size();
        runtime::Message credit;
        credit.kind = runtime::MessageKind::merge_credit;
        credit.lease = m->lease;
        credit.number = 1;
        link.send(credit);
      }
      done(*m, false);
      break;
    }
    case runtime::MessageKind::wait: std::this_thread::sleep_for(std::chrono::milliseconds(m->number)); break;
    case runtime::MessageKind::finished:
      if (m->number == 1) done(*m, true);
      std::this_thread::sleep_for(100ms); // the last message leaves before the link closes
      return;
    case runtime::MessageKind::surface_credit: continue;
    default: break;
    }
    ask();
  }
}

// The workers run in a child process, forked before the manager makes its ZeroMQ context, so that
// the manager's CPU (its whole process, as in a real run) holds none of theirs. The child reads the
// endpoint, the key file and one token a line from `in`.
void workers_process(int in, std::size_t rows, std::size_t surface) {
  std::string text;
  char buffer[4096];
  for (ssize_t n; (n = ::read(in, buffer, sizeof buffer)) > 0;)
    text.append(buffer, static_cast<std::size_t>(n));
  std::vector<std::string> lines = bench::split(text);
  if (lines.size() < 3) return;
  ::setenv("GEOTANDEM_CURVE_KEY_FILE", lines[1].c_str(), 1);
  std::atomic<std::uint64_t> next_key{1};
  std::vector<std::thread> workers;
  for (std::size_t i = 2; i < lines.size(); ++i)
    workers.emplace_back(idle_worker, lines[0], lines[i], rows, surface, std::ref(next_key));
  for (auto& t : workers)
    t.join();
}

} // namespace

int bench_main(int argc, char** argv) {
  const bench::Args args(argc, argv,
                         "bench_manager_cost [cube=256,256,64] [leaf=8] [workers=2,8,64] [rows=1] [surface=4096]");
  const std::vector<std::int64_t> shape = args.integers(1, "256,256,64", 2);
  if (shape.size() != 3) args.fail(1, "is not three sizes X,Y,Z");
  const std::int64_t leaf = args.integer(2, 8, 1);
  const std::vector<std::int64_t> counts = args.integers(3, "2,8,64", 1);
  const auto rows = static_cast<std::size_t>(args.integer(4, 1, 0));
  const auto surface = static_cast<std::size_t>(args.integer(5, 4096, 1));
  const fs::path root = fs::temp_directory_path() / ("geotandem_bench_manager_" + std::to_string(getpid()));
  volume::Geometry geometry;
  geometry.shape = {shape[0] + 1, shape[1] + 1, shape[2] + 1}; // samples: one more than cells
  std::printf("manager cost: cube of %lld x %lld x %lld cells, leaves of %lld, %zu index row(s) per EXTRACT, "
              "surfaces of %zu bytes; workers in process, answering at once (uptime: see the caller)\n",
              static_cast<long long>(shape[0]), static_cast<long long>(shape[1]), static_cast<long long>(shape[2]),
              static_cast<long long>(leaf), rows, surface);
  std::printf("%8s %8s %8s %9s %9s %10s %10s %9s %11s %11s\n", "workers", "leaves", "tasks", "wall_s", "mgr_cpu_s",
              "us/message", "us/task", "kmsg/s", "rows/s", "mgr_share");
  for (const std::int64_t w : counts) {
    std::fflush(stdout); // the child would print what is buffered again
    int fds[2];
    if (::pipe(fds) != 0) throw std::runtime_error("pipe");
    const pid_t child = ::fork();
    if (child == 0) {
      ::close(fds[1]);
      workers_process(fds[0], rows, surface);
      std::fflush(nullptr);
      ::_exit(0);
    }
    ::close(fds[0]);
    const fs::path dir = root / ("w" + std::to_string(w));
    auto store = store::ComponentStore::create(dir, geometry);
    runtime::ManagerOptions options;
    options.settings.volume = R"({"kind":"none"})";
    options.settings.store = dir.string();
    options.settings.extraction.block_size = leaf;
    options.settings.run = store.begin_run("{}");
    options.workers = static_cast<std::size_t>(w);
    NullProgress progress;
    CancelToken cancel;
    runtime::Manager manager(options, store, nullptr, Logger::null(), progress, cancel);
    std::string handout = manager.endpoint() + "," + std::getenv("GEOTANDEM_CURVE_KEY_FILE");
    for (std::int64_t i = 0; i < w; ++i)
      handout += "," + manager.new_token();
    if (::write(fds[1], handout.data(), handout.size()) != static_cast<ssize_t>(handout.size()))
      throw std::runtime_error("cannot hand the tokens to the workers");
    ::close(fds[1]);
    const runtime::ManagerReport r = manager.run();
    int status = 0;
    ::waitpid(child, &status, 0);
    const std::uint64_t tasks = r.extract + r.send + r.merge + r.finish;
    const double messages = static_cast<double>(r.messages_in + r.messages_out);
    const double rows_total = static_cast<double>(r.components + r.duplicates);
    std::printf("%8lld %8zu %8llu %9.2f %9.2f %10.1f %10.1f %9.1f %11.0f %10.0f%%\n", static_cast<long long>(w),
                r.leaves, static_cast<unsigned long long>(tasks), r.seconds, r.manager_cpu_seconds,
                1e6 * r.manager_cpu_seconds / messages, 1e6 * r.manager_cpu_seconds / static_cast<double>(tasks),
                messages / r.manager_cpu_seconds / 1000.0, r.commit_seconds > 0 ? rows_total / r.commit_seconds : 0.0,
                100.0 * r.manager_cpu_seconds / r.seconds);
    std::fflush(stdout);
  }
  std::error_code ec;
  fs::remove_all(root, ec);
  return 0;
}

int main(int argc, char** argv) {
  return geotandem::bench::guarded_main("bench_manager_cost", [&] { return bench_main(argc, argv); });
}
