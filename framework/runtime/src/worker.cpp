// The worker's task loop (worker.hpp).
#include "geotandem/runtime/worker.hpp"

#include <sys/prctl.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cmath>
#include <csignal>
#include <cstdlib>
#include <ctime>
#include <functional>
#include <optional>
#include <thread>
#include <utility>

#include "batch_extract.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/runtime/launcher.hpp"
#include "geotandem/runtime/manager.hpp"
#include "geotandem/runtime/surface_chunks.hpp"
#include "geotandem/store/shard.hpp"
#include "geotandem/tandem/blocks.hpp"
#include "geotandem/tandem/marching_cubes.hpp"
#include "geotandem/tandem/serialize.hpp"
#include "manager_support.hpp"
#include "shard_sink.hpp"
#include "walltime.hpp"
#include "worker_failure.hpp"
#include "worker_link.hpp"

namespace geotandem::runtime {

namespace {

using Clock = std::chrono::steady_clock;

class Worker {
public:
  Worker(const WorkerOptions& options, const VolumeFactory& factory, Logger& log, const CancelToken& cancel)
      : options_(options), factory_(factory), log_(log), cancel_(cancel),
        link_(context_,
              {.endpoint = options.endpoint,
               .token = options.token,
               .heartbeat = options.heartbeat,
               .manager_timeout = options.manager_timeout},
              cancel_) {}

  int run() {
    Message hello;
    hello.kind = MessageKind::hello;
    hello.text = options_.token;
    hello.number = static_cast<std::uint64_t>(getpid());
    link_.send(hello);
    for (;;) {
      const Message m = next();
      try {
        if (handle(m)) return 0;
      } catch (const StopRequested&) {
        return 0;
      } catch (const Cancelled&) {
        throw;
      } catch (const std::exception& e) {
        Message f;
        f.kind = MessageKind::failed;
        f.lease = m.lease;
        f.text = e.what();
        f.number = static_cast<std::uint64_t>(detail::failure_code(e));
        link_.send(f);
        throw;
      }
    }
  }

  // The error to report when a cancel ended the worker because its manager went silent (the link
  // cancels the task in progress); none when a signal stopped it.
  std::optional<Error> manager_gone() const {
    if (!link_.gone()) return std::nullopt;
    const auto ms = link_.manager_timeout().count();
    const std::string seconds = std::to_string(ms / 1000) + (ms % 1000 ? "." + std::to_string(ms % 1000 / 100) : "");
    return Error("the manager at " + link_.endpoint() + " has been silent for " + seconds + " s: it is gone",
                 {.worker = options_.token}, "this worker stops; rerun the extraction to resume");
  }

private:
  // Runs one task; true when the worker must stop.
  bool handle(const Message& m) {
    {
      task_lease_ = m.lease;
      task_cpu_start_ = detail::cpu_seconds();
      switch (m.kind) {
      case MessageKind::setup: setup(m); break;
      case MessageKind::extract: extract(m); break;
      case MessageKind::send: send_surface(m); break;
      case MessageKind::merge: merge(m); break;
      case MessageKind::wait:
        std::this_thread::sleep_for(std::chrono::milliseconds(std::min<std::uint64_t>(m.number, 2000)));
        break;
      case MessageKind::finished:
        if (m.number == 1) finish(m);
        return true;
      case MessageKind::surface_credit: return false; // the last credits of a SEND already over
      default:
        log_.warning("worker " + options_.token + ": unexpected " + to_string(m.kind) + " dropped");
        return false;
      }
      if (retiring_) {
        // Nobody took its surface in time: it leaves before the scheduler kills it (the manager
        // re-does what it holds).
        if (m.kind == MessageKind::wait && detail::walltime_nearly_over()) {
          log_.warning("worker " + options_.token + ": no worker took its surface before its walltime; it leaves");
          return true;
        }
      } else if (const std::string why = m.kind == MessageKind::setup ? std::string() : detail::walltime_exhausted();
                 !why.empty()) {
        // Near the walltime (never right after SETUP: every worker does some work): it takes no
        // more EXTRACT and hands back what it holds when the manager says where.
        log_.warning("worker " + options_.token + ": near its walltime, retires: " + why);
        retiring_ = true;
        Message r;
        r.kind = MessageKind::retire;
        r.text = why;
        link_.send(r); // asks for its next task, as ASK does
        return false;
      }
      ask();
      return false;
    }
  }
  Message next() {
    for (;;) {
      cancel_.throw_if_cancelled();
      try {
        if (std::optional<Message> m = link_.receive(std::chrono::milliseconds(200))) return *m;
      } catch (const ProtocolError& e) {
        log_.warning("worker " + options_.token + ": dropped a damaged message: " + e.what());
      }
    }
  }

  void ask() {
    Message m;
    m.kind = MessageKind::ask;
    link_.send(m);
  }

  void setup(const Message& m) {
    settings_ = RunSettings::from_json(m.text);
    volume_ = factory_(settings_.volume);
    writer_.emplace(settings_.store, options_.token, volume_->geometry());
    sink_.emplace(*writer_, settings_.run, [this] { send_commit(task_lease_); });
    options_tandem_ = tandem::loop_options(settings_.extraction);
    options_tandem_.cancel = &cancel_;
    log_.info("worker " + options_.token + ": ready (" + volume_->source() + ")");
  }

  void need_setup(const Message& m) const {
    if (!volume_)
      throw Error(std::string(to_string(m.kind)) + " before SETUP", {.worker = options_.token},
                  "the manager speaks another protocol: run the same geotandem version everywhere");
  }

  // The components written since the last COMMIT, synced, to the manager.
  void send_commit(const Lease& lease) {
    Message c;
    c.kind = MessageKind::commit;
    c.lease = lease;
    c.entries = sink_->take();
    if (!c.entries.empty()) link_.send(c);
  }

  void report(const Message& task, Clock::time_point start, bool final = false) {
    send_commit(task.lease);
    Message d;
    d.kind = MessageKind::done;
    d.lease = task.lease;
    const auto spent = Clock::now() - start;
    d.number =
        static_cast<std::uint64_t>(std::llround((detail::cpu_seconds() - task_cpu_start_) * 1e6)); // CPU microseconds
    // 5: the same in microseconds, for the task log (a leaf of an empty region takes well under 1 ms).
    d.box[5] = std::chrono::duration_cast<std::chrono::microseconds>(spent).count();
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    d.box[0] = u.ru_maxrss;
    // 1: this worker's surface holds nothing after the task; every component of its leaves is in
    // the COMMIT above, so the manager records the leaves as finished (resume) and, after an
    // EXTRACT or a MERGE, schedules nothing more for them (issue 55): the worker drops the empty
    // surface and its region, and nothing is sent or merged for it. Its counters go with the DONE,
    // so that the run's totals keep them.
    const bool empty = !surface_ || surface_->component_count() == 0;
    // 2 (added to 1): the leaves this EXTRACT gave left nothing open by themselves (the task log's
    // record of which leaves are empty, for the scale model).
    d.box[1] = (empty ? 1 : 0) + (piece_empty_ ? 2 : 0);
    d.box[2] = static_cast<std::int64_t>(totals_.input_triangles);
    d.box[3] = static_cast<std::int64_t>(totals_.collapses);
    // 4: the triangles this worker's surface holds after the task (the run's triangles held).
    d.box[4] = surface_ ? static_cast<std::int64_t>(surface_->triangle_count()) : 0;
    d.bytes = batch_merges_; // an EXTRACT's merges inside its batch (batch_extract.hpp)
    if (final) {
      d.text = counters_to_json(totals_); // every counter of the whole surface
    } else if (empty && surface_) {
      const tandem::SimplifyCounters dropped = surface_->counters();
      if (dropped.input_triangles > 0 || dropped.evaluations > 0) d.text = counters_to_json(dropped);
      surface_.reset();
    }
    link_.send(d);
  }

  void extract(const Message& m) {
    need_setup(m);
    const auto start = Clock::now();
    const volume::Box cells{{m.box[0], m.box[1], m.box[2]}, {m.box[3], m.box[4], m.box[5]}};
    piece_empty_ = false;
    const bool brute = settings_.extraction.mode == tandem::ExtractMode::brute;
    const std::int64_t leaf = tandem::leaf_size(settings_.extraction, volume_->geometry().shape);
    // A leaf, or a batch: a subtree's leaves but the finished ones the bytes name (batch_extract.hpp).
    detail::BatchMerges merges;
    std::unique_ptr<tandem::WorkingSurface> piece = detail::extract_batch(
        *volume_, cells, leaf, detail::decode_runs(m.bytes), options_tandem_, &*sink_, brute, &merges);
    piece_empty_ = !piece || piece->component_count() == 0;
    const auto absorbing = Clock::now();
    const bool into = surface_ && piece;
    absorb(std::move(piece));
    if (into) merges.absorb_seconds = std::chrono::duration<double>(Clock::now() - absorbing).count();
    batch_merges_ = detail::encode_merges(merges);
    report(m, start);
    piece_empty_ = false;
    batch_merges_.clear();
  }

  void absorb(std::unique_ptr<tandem::WorkingSurface> piece) {
    if (!piece) return; // every leaf of the batch was finished
    if (!surface_)
      surface_ = std::move(piece);
    else
      surface_->merge(std::move(*piece), &cancel_);
  }

  // The manager gave up on this worker during a transfer (FINISHED): it stops.
  struct StopRequested {};

  // The next message of the transfer under `lease` of kind `kind`; other messages of the task's
  // time are dropped (logged), FINISHED stops the worker.
  Message transfer_message(const Lease& lease, MessageKind kind) {
    for (;;) {
      Message r = next();
      if (r.kind == kind && r.lease == lease) return r;
      if (r.kind == MessageKind::finished) throw StopRequested{};
      log_.warning("worker " + options_.token + ": " + to_string(r.kind) + " dropped during a transfer");
    }
  }

  // SEND: the surface in chunks, at most kChunkWindow ahead of the manager's credits, then its
  // total size and checksum.
  void send_surface(const Message& m) {
    need_setup(m);
    std::vector<std::byte> record;
    if (surface_) record = tandem::serialize(*surface_);
    surface_.reset();
    if (record.size() > kDefaultMaxSurface)
      throw InvalidArgument("a partial surface of " + std::to_string(record.size() >> 20) + " MiB is over the cap of " +
                                std::to_string(kDefaultMaxSurface >> 20) + " MiB",
                            {.worker = options_.token}, "use smaller blocks (--block-size)");
    std::size_t ahead = 0;
    std::uint64_t offset = 0;
    for (std::span<const std::byte> piece : cut_into_chunks(record, settings_.chunk_bytes)) {
      while (ahead >= kChunkWindow)
        ahead -= std::min<std::size_t>(ahead, transfer_message(m.lease, MessageKind::surface_credit).number);
      Message c;
      c.kind = MessageKind::surface_chunk;
      c.lease = m.lease;
      c.number = offset;
      if (offset == 0) c.box[0] = static_cast<std::int64_t>(record.size()); // the manager's room for it
      c.bytes.assign(piece.begin(), piece.end());
      link_.send(c);
      offset += piece.size();
      ++ahead;
    }
    Message end;
    end.kind = MessageKind::surface;
    end.lease = m.lease;
    end.number = record.size();
    end.box[0] = static_cast<std::int64_t>(surface_checksum(record));
    link_.send(end);
  }

  // MERGE: the announced surface arrives in chunks (each acknowledged with a credit), is checked
  // against its size and checksum, and goes straight into this worker's surface (no engine is
  // rebuilt for the sender); a worker holding nothing takes the record as its surface.
  void merge(const Message& m) {
    need_setup(m);
    const auto start = Clock::now();
    SurfaceAssembler in(kDefaultMaxSurface, m.number, settings_.chunk_bytes);
    while (!in.complete() && !in.broken()) {
      const Message c = transfer_message(m.lease, MessageKind::merge_chunk);
      if (const std::optional<std::string> why = in.add(c.number, c.bytes))
        log_.warning("worker " + options_.token + ": dropped " + *why);
      Message credit;
      credit.kind = MessageKind::merge_credit;
      credit.lease = m.lease;
      credit.number = 1;
      link_.send(credit);
    }
    if (const std::optional<std::string> why = in.finish(m.number, static_cast<std::uint64_t>(m.box[0])))
      throw DataError("the partial surface to merge is damaged: " + *why, {.worker = options_.token},
                      "rerun the same command: committed components are kept");
    const std::vector<std::byte> record = in.take();
    try {
      if (surface_)
        tandem::merge_record(*surface_, record, &cancel_);
      else
        surface_ = std::make_unique<tandem::WorkingSurface>(tandem::deserialize(record, &*sink_));
    } catch (const DataError& e) {
      // A record that is not a surface this run's workers write (checked before it touches this
      // worker's surface, tandem/src/surface_check.hpp), or one that does not weld to it. The
      // worker fails the task and stops: the manager re-does its blocks and the record's.
      surface_.reset();
      throw DataError("refused the partial surface it was to merge: " + e.message(),
                      {.block = e.context().block, .worker = options_.token},
                      "its blocks and the record's are extracted again by another worker");
    }
    report(m, start);
  }

  void finish(const Message& m) {
    need_setup(m);
    const auto start = Clock::now();
    if (surface_) {
      // The final surface covers every leaf but those an earlier run finished (resume): those
      // held nothing, so the whole cube is this surface's region and no face is open any more.
      const volume::Box cube = tandem::cube_cells(volume_->geometry().shape);
      const tandem::Region& region = surface_->region();
      if (region.blocks().size() != 1 || !(region.blocks().front() == cube))
        surface_->set_region(tandem::Region::block(cube, cube));
      surface_->finish(&cancel_);
      totals_ = surface_->counters();
    }
    surface_.reset();
    report(m, start, true);
  }

  WorkerOptions options_;
  const VolumeFactory& factory_;
  Logger& log_;
  CancelToken cancel_;
  zmq::context_t context_{1};
  detail::WorkerLink link_;
  RunSettings settings_;
  tandem::TandemOptions options_tandem_;
  std::shared_ptr<const volume::Volume> volume_;
  std::optional<store::ShardWriter> writer_;
  std::optional<detail::ShardSink> sink_;
  std::unique_ptr<tandem::WorkingSurface> surface_;
  Lease task_lease_;                    // of the task in progress (mid-task COMMITs carry it)
  bool retiring_ = false;               // near its walltime: RETIRE sent
  bool piece_empty_ = false;            // the EXTRACT in progress gave an empty piece
  std::vector<std::byte> batch_merges_; // of the EXTRACT in progress (batch_extract.hpp)
  double task_cpu_start_ = 0.0;         // this process's CPU seconds when the task began
  tandem::SimplifyCounters totals_;     // of the whole surface, once finished
};

} // namespace

namespace {

// A local worker ends with its manager: SIGTERM (a cancel, as Ctrl-C) when the parent dies, and
// at once when it is already gone. Without it an orphan kept writing its shard until the
// heartbeat timeout after a SIGKILL of the manager.
void end_with_local_manager(Logger& log, const std::string& token) {
  const char* text = std::getenv(manager_pid_variable);
  if (!text || !*text) return;
  const long manager = std::strtol(text, nullptr, 10);
  if (manager <= 0) return;
  ::prctl(PR_SET_PDEATHSIG, SIGTERM);
  if (::getppid() != static_cast<pid_t>(manager)) {
    log.warning("worker " + token + ": its manager (pid " + std::to_string(manager) + ") is already gone");
    throw Cancelled();
  }
}

} // namespace

int run_worker(const WorkerOptions& options, const VolumeFactory& factory, Logger& log, const CancelToken& cancel) {
  store::validate_writer_name(options.token);
  end_with_local_manager(log, options.token);
  // Each leaf's surface takes over the mesh storage the one before it left (it is merged into the
  // worker's surface and dropped): no fresh pages faulted in and no growth by copies, leaf after
  // leaf. Given back when the worker ends.
  struct KeepSurfaceStorage {
    KeepSurfaceStorage() { tandem::keep_surface_storage(true); }
    ~KeepSurfaceStorage() { tandem::keep_surface_storage(false); }
    KeepSurfaceStorage(const KeepSurfaceStorage&) = delete;
    KeepSurfaceStorage& operator=(const KeepSurfaceStorage&) = delete;
  } keep;
  Worker worker(options, factory, log, cancel);
  try {
    return worker.run();
  } catch (const Cancelled&) {
    if (std::optional<Error> gone = worker.manager_gone()) throw *gone;
    throw;
  }
}

} // namespace geotandem::runtime
