// A worker handed a forged partial surface (issue 52): one of the run's workers ships a record
// whose content is wrong but whose length and checksum are right. The worker that is to merge it
// refuses it with a DataError naming itself and the record's blocks, the run re-does the blocks of
// both, and the store ends with the components of the in-process run.
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <limits>
#include <sstream>
#include <thread>
#include <zmq.hpp>

#include "../../framework/runtime/src/worker_link.hpp"
#include "geotandem/core/error.hpp"
#include "geotandem/runtime/manager.hpp"
#include "geotandem/runtime/surface_chunks.hpp"
#include "geotandem/tandem/marching_cubes.hpp"
#include "geotandem/tandem/serialize.hpp"
#include "geotandem/tandem/tandem.hpp"
#include "geotandem/volume/io.hpp"
#include "process_fixtures.hpp"
#include "scratch.hpp"
#include "surface_record_layout.hpp"
#include "test_paths.hpp"

namespace geotandem::runtime {
namespace {

using namespace std::chrono_literals;

// The forgery: every vertex loses its lattice id (so nothing would weld: on main such a record
// merged, leaving holes along the seam) and a triangle names a vertex beyond the last (on main, a
// SIGSEGV in absorb_state).
void forge(std::vector<std::byte>& record) {
  const testing::RecordLayout l(record);
  for (std::size_t i = 0; i < l.nv; ++i)
    testing::record_put(record, l.vertex(i) + testing::RecordLayout::kLatticeId,
                        std::numeric_limits<std::uint64_t>::max());
  testing::record_put(record, l.corner(l.nt / 2, 1), static_cast<std::uint32_t>(l.nv + 7));
  testing::reseal(record);
}

// One of the run's workers (its token from the manager) that speaks the protocol itself: it
// extracts its leaves and merges what it is sent as a worker does, without writing components (it
// never reports its surface empty, so its leaves are not recorded finished), and ships its first
// SEND that holds triangles forged: once it holds triangles it retires, and the manager has it
// hand its surface to the real worker. Then it leaves; the manager re-does what it held.
class Forger {
public:
  Forger(std::string endpoint, std::string token, const std::string& cube)
      : endpoint_(std::move(endpoint)), token_(std::move(token)), volume_(volume::open_volume(cube)) {}

  void run(const std::atomic<bool>& stop) {
    zmq::context_t context(1);
    detail::WorkerLink link(context, {.endpoint = endpoint_, .token = token_}, cancel_);
    Message hello;
    hello.kind = MessageKind::hello;
    hello.text = token_;
    hello.number = static_cast<std::uint64_t>(getpid());
    link.send(hello);
    while (!stop) {
      const std::optional<Message> m = link.receive(200ms);
      if (!m) continue;
      switch (m->kind) {
      case MessageKind::setup: options_ = tandem::loop_options(RunSettings::from_json(m->text).extraction); break;
      case MessageKind::extract: extract(*m), done(link, *m); break;
      case MessageKind::merge: merge(link, *m), done(link, *m); break;
      case MessageKind::send:
        if (send(link, *m)) return; // forged: it leaves
        break;
      case MessageKind::wait:
        std::this_thread::sleep_for(std::chrono::milliseconds(std::min<std::uint64_t>(m->number, 200)));
        break;
      default: return; // FINISHED (or anything else): it leaves
      }
      // Once it holds triangles it retires (as a worker near its walltime does), so that the
      // manager has it hand its surface to a real worker at once.
      Message ask;
      ask.kind = MessageKind::ask;
      if (!retired_ && surface_ && surface_->triangle_count() > 0) {
        ask.kind = MessageKind::retire;
        ask.text = "a forger";
        retired_ = true;
      }
      link.send(ask);
    }
  }
  bool forged() const { return forged_; }

private:
  void extract(const Message& m) {
    const volume::Box cells{{m.box[0], m.box[1], m.box[2]}, {m.box[3], m.box[4], m.box[5]}};
    std::unique_ptr<tandem::WorkingSurface> piece;
    tandem::extract_block(*volume_, cells, options_, nullptr, &piece);
    if (!surface_)
      surface_ = std::move(piece);
    else
      surface_->merge(std::move(*piece));
  }
  void done(detail::WorkerLink& link, const Message& m) {
    Message d;
    d.kind = MessageKind::done;
    d.lease = m.lease;
    d.box[1] = 0; // never "empty": its leaves' components were not written
    link.send(d);
  }
  // The announced record, chunk by chunk under credits, merged into its surface.
  void merge(detail::WorkerLink& link, const Message& m) {
    std::vector<std::byte> record(m.number);
    std::uint64_t got = 0;
    while (got < m.number) {
      const std::optional<Message> c = link.receive(200ms);
      if (!c || c->kind != MessageKind::merge_chunk || !(c->lease == m.lease)) continue;
      std::copy(c->bytes.begin(), c->bytes.end(), record.begin() + static_cast<long>(c->number));
      got += c->bytes.size();
      Message credit;
      credit.kind = MessageKind::merge_credit;
      credit.lease = m.lease;
      credit.number = 1;
      link.send(credit);
    }
    if (surface_)
      tandem::merge_record(*surface_, record);
    else
      surface_ = std::make_unique<tandem::WorkingSurface>(tandem::deserialize(record, nullptr));
  }
  // Its surface as SURFACE-CHUNKs (small records: within the window of credits) and SURFACE.
  bool send(detail::WorkerLink& link, const Message& m) {
    std::vector<std::byte> record;
    if (surface_) record = tandem::serialize(*surface_);
    surface_.reset();
    const bool forging = !record.empty() && testing::RecordLayout(record).nt > 0;
    if (forging) forge(record);
    std::uint64_t offset = 0;
    for (std::span<const std::byte> piece : cut_into_chunks(record, 64 * 1024)) {
      Message c;
      c.kind = MessageKind::surface_chunk;
      c.lease = m.lease;
      c.number = offset;
      c.bytes.assign(piece.begin(), piece.end());
      link.send(c);
      offset += piece.size();
    }
    Message end;
    end.kind = MessageKind::surface;
    end.lease = m.lease;
    end.number = record.size();
    end.box[0] = static_cast<std::int64_t>(surface_checksum(record));
    link.send(end);
    forged_ = forged_ || forging;
    return forging;
  }

  std::string endpoint_, token_;
  std::unique_ptr<volume::Volume> volume_;
  CancelToken cancel_;
  tandem::TandemOptions options_;
  std::unique_ptr<tandem::WorkingSurface> surface_;
  std::atomic<bool> forged_{false};
  bool retired_ = false;
};

TEST(ForgedRecord, TheWorkerRefusesItNamingItselfAndTheBlocksAndTheRunRedoesThem) {
  testing::ScratchDir dir;
  const std::string cube = dir.file("cube.raw");
  auto r = testing::run_geotandem("-q synth --kind analytic --shape 48 44 40 --seed 3 --out '" + cube + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = testing::run_geotandem("-q extract '" + cube + "' --iso 0.5 --block-size 8 --workers 0 --out '" +
                             dir.file("ref") + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;

  const auto volume = volume::open_volume(cube);
  auto store = store::ComponentStore::create(dir.file("store"), volume->geometry());
  ManagerOptions options;
  options.settings.volume = R"({"kind":"file","path":")" + cube + R"(","nan":"error","variable":""})";
  options.settings.store = dir.file("store");
  options.settings.extraction.block_size = 8;
  options.settings.extraction.iso = 0.5f;
  options.settings.run = store.begin_run("{}");
  options.worker_command = {test_paths::binary(), "-q", "worker"};
  options.workers = 1;
  LocalLauncher launcher;
  std::ostringstream text;
  Logger log(text, LogLevel::info);
  CancelToken cancel;
  NullProgress progress;
  Manager manager(options, store, &launcher, log, progress, cancel);
  Forger forger(manager.endpoint(), manager.new_token(), cube);
  std::atomic<bool> stop{false};
  std::thread forging([&] { forger.run(stop); });
  ManagerReport report;
  EXPECT_NO_THROW(report = manager.run());
  stop = true;
  forging.join();
  const std::string log_text = text.str();

  ASSERT_TRUE(forger.forged()) << "the forger was never asked for a surface holding triangles:\n" << log_text;
  // The refusal names the worker that refused and the record's blocks, and says it was refused.
  const std::size_t at = log_text.find("refused the partial surface it was to merge");
  ASSERT_NE(at, std::string::npos) << log_text;
  const std::string line =
      log_text.substr(log_text.rfind('\n', at) + 1, log_text.find('\n', at) - log_text.rfind('\n', at));
  EXPECT_NE(line.find("worker w"), std::string::npos) << line;
  EXPECT_NE(line.find("blocks ["), std::string::npos) << line;
  EXPECT_NE(log_text.find("refused the partial surface it was to merge during", at), std::string::npos)
      << log_text; // the manager's warning that its blocks are re-done
  EXPECT_GE(report.deaths, 1u);
  EXPECT_GT(report.redone_leaves, 0u);

  // The store holds the in-process run's components, each read back intact.
  const auto expected = testing::components_of(dir.file("ref"), false);
  const auto got = testing::components_of(dir.file("store"), true);
  ASSERT_EQ(got.size(), expected.size());
  for (const auto& [key, c] : expected) {
    ASSERT_TRUE(got.count(key)) << key;
    EXPECT_NEAR(got.at(key).volume, c.volume, 0.005 * std::abs(c.volume) + 1e-9);
    EXPECT_EQ(got.at(key).closed, c.closed) << key;
  }
}

} // namespace
} // namespace geotandem::runtime
