#pragma once
// The manager as a library with real sockets, for the manager's tests (manager_test.cpp,
// manager_trust_test.cpp): a run over a small analytic cube, its in-process reference, and a
// peer's socket made a worker of the run.
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <thread>
#include <zmq.hpp>

#include "geotandem/core/error.hpp"
#include "geotandem/runtime/manager.hpp"
#include "geotandem/volume/io.hpp"
#include "process_fixtures.hpp"
#include "scratch.hpp"
#include "test_paths.hpp"

namespace geotandem::runtime::testing_manager {

using testing::ScratchDir;

struct ManagerRun {
  ScratchDir dir;
  std::string cube = dir.file("cube.raw");
  std::unique_ptr<volume::Volume> volume;
  std::optional<store::ComponentStore> store;
  ManagerOptions options;
  CancelToken cancel;
  NullProgress progress;

  explicit ManagerRun(const std::string& shape = "40 40 40") {
    auto r = testing::run_geotandem("-q synth --kind analytic --shape " + shape + " --seed 3 --out '" + cube + "'");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    volume = volume::open_volume(cube);
    store = store::ComponentStore::create(dir.file("store"), volume->geometry());
    options.settings.volume = R"({"kind":"file","path":")" + cube + R"(","nan":"error","variable":""})";
    options.settings.store = dir.file("store");
    options.settings.extraction.block_size = 8;
    options.settings.extraction.iso = 0.5f;
    options.settings.run = store->begin_run("{}");
    options.worker_command = {test_paths::binary(), "-q", "worker"};
  }

  // A manager with local workers over this run's options: its report (none when it threw: a
  // failure), its log in `log_text`.
  std::optional<ManagerReport> run_manager(LogLevel level, std::string& log_text) {
    LocalLauncher launcher;
    std::ostringstream text;
    Logger log(text, level);
    Manager manager(options, *store, &launcher, log, progress, cancel);
    std::optional<ManagerReport> report;
    try {
      report = manager.run();
    } catch (const std::exception& e) {
      ADD_FAILURE() << e.what();
    }
    log_text = text.str();
    return report;
  }

  // The same cube extracted in one process (`ref`), what a run with workers must give.
  bool extract_reference() {
    auto r = testing::run_geotandem("-q extract '" + cube + "' --iso 0.5 --block-size 8 --workers 0 --out '" +
                                    dir.file("ref") + "'");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return r.exit_code == 0;
  }
  // The store holds the reference's components (keys), volumes within 0.5 %; `check_records`
  // reads every record back as well.
  void expect_reference_components(bool check_records) {
    const auto expected = testing::components_of(dir.file("ref"), false);
    const auto got = testing::components_of(dir.file("store"), check_records);
    ASSERT_EQ(got.size(), expected.size());
    for (const auto& [key, c] : expected) {
      ASSERT_TRUE(got.count(key)) << key;
      EXPECT_NEAR(got.at(key).volume, c.volume, 0.005 * std::abs(c.volume) + 1e-9);
    }
  }
};

// The message of the geotandem::Error `f` throws; empty when it throws none.
inline std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// Makes `dealer` a CURVE client with the run's worker keys, as a worker started by this process
// finds them (GEOTANDEM_CURVE_KEY_FILE, which the manager sets).
inline void use_worker_keys(zmq::socket_t& dealer) {
  const char* file = std::getenv("GEOTANDEM_CURVE_KEY_FILE");
  ASSERT_NE(file, nullptr) << "the manager should hand its workers a key file";
  std::ifstream in(file);
  std::map<std::string, std::string> keys;
  std::string name, value;
  while (in >> name >> value)
    keys[name] = value;
  dealer.set(zmq::sockopt::curve_serverkey, keys["server"]);
  dealer.set(zmq::sockopt::curve_publickey, keys["public"]);
  dealer.set(zmq::sockopt::curve_secretkey, keys["secret"]);
}

} // namespace geotandem::runtime::testing_manager
