// The manager and its workers in two network namespaces joined by a veth pair, as on two hosts:
// the manager binds its side's address (CurveZMQ on, as off loopback), the workers run as jobs of
// the LSF stand-ins submitted into the other namespace, and the run gives the components of the
// in-process run. A worker with a wrong key, and one without CURVE, are refused and logged.
// Needs root and `ip netns`; skips with a message when namespaces cannot be made.
#include <sys/stat.h>
#include <unistd.h>

#include <fstream>
#include <zmq.h>

#include "cluster_run.hpp"
#include "test_paths.hpp"

namespace geotandem::testing {
namespace {

namespace fs = std::filesystem;

int sh(const std::string& command) {
  const int status = std::system((command + " >/dev/null 2>&1").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// `ip netns exec NS ARGV...` in the background, stdout and stderr to `log`.
pid_t spawn_in(const std::string& ns, std::vector<std::string> argv, const std::string& log) {
  argv.insert(argv.begin(), {"ip", "netns", "exec", ns});
  return spawn_logged(std::move(argv), log);
}

struct TwoHosts : ::testing::Test {
  ScratchDir dir;
  const int n = static_cast<int>(getpid() % 200) + 20;
  const std::string ns_manager = "gtm" + std::to_string(getpid()), ns_workers = "gtw" + std::to_string(getpid());
  const std::string manager_ip = "10.213." + std::to_string(n) + ".1", worker_ip = "10.213." + std::to_string(n) + ".2";
  bool made = false;

  void SetUp() override {
    if (sh("ip netns add " + ns_manager) != 0 || sh("ip netns add " + ns_workers) != 0)
      GTEST_SKIP() << "cannot create network namespaces here (needs root and iproute2's `ip netns`)";
    made = true;
    const std::string a = "gva" + std::to_string(getpid() % 100000), b = "gvb" + std::to_string(getpid() % 100000);
    for (const std::string& c :
         {"ip link add " + a + " netns " + ns_manager + " type veth peer name " + b + " netns " + ns_workers,
          "ip -n " + ns_manager + " addr add " + manager_ip + "/24 dev " + a,
          "ip -n " + ns_workers + " addr add " + worker_ip + "/24 dev " + b,
          "ip -n " + ns_manager + " link set " + a + " up", "ip -n " + ns_workers + " link set " + b + " up",
          "ip -n " + ns_manager + " link set lo up", "ip -n " + ns_workers + " link set lo up"})
      ASSERT_EQ(sh(c), 0) << c;
    // bsub that submits into the workers' namespace: the stand-in's jobs then run there.
    fs::create_directories(dir.file("bin"));
    std::ofstream(dir.file("bin/bsub")) << "#!/bin/sh\nexec ip netns exec " << ns_workers << " '"
                                        << test_paths::lsf_standin() << "/bsub' \"$@\"\n";
    fs::permissions(dir.file("bin/bsub"), fs::perms::owner_all);
  }
  void TearDown() override {
    if (!made) return;
    sh("ip netns del " + ns_manager);
    sh("ip netns del " + ns_workers);
  }
};

std::string key_line(const std::string& file, const std::string& name) {
  std::ifstream in(file);
  std::string k, v;
  while (in >> k >> v)
    if (k == name) return v;
  return {};
}

TEST_F(TwoHosts, WorkersInTheOtherNamespaceRunWithCurveAndWrongKeysAreRefused) {
  const std::string reference = dir.file("local");
  auto r = run_geotandem("-q" + shell_args(cluster_args(reference, "local", 1)));
  ASSERT_EQ(r.exit_code, 0) << r.err;

  EnvGuard path{"PATH", dir.file("bin") + ":" + path_with(test_paths::lsf_standin())};
  EnvGuard state{"LSF_STANDIN_DIR", dir.file("lsf-state")};
  const std::string out = dir.file("run"), log = dir.file("manager.log");
  std::vector<std::string> args{test_paths::binary()};
  for (const std::string& a : cluster_args(out, "lsf", 2))
    args.push_back(a);
  // The store named with a trailing slash: its keys still go beside it, not inside it.
  args.insert(args.end(), {"--bind", manager_ip, "--set", "output.store=store/"});
  const pid_t manager = spawn_in(ns_manager, args, log);
  ASSERT_TRUE(wait_for_text(log, "joined; 2 connected", manager, 300)) << read_text(log);
  std::string text = read_text(log);
  EXPECT_NE(text.find("CurveZMQ is on"), std::string::npos) << text;
  const auto at = text.find("manager listening on ");
  ASSERT_NE(at, std::string::npos) << text;
  const std::string endpoint = text.substr(at + 21, text.find(';', at) - at - 21);
  EXPECT_EQ(endpoint.rfind("tcp://" + manager_ip + ":", 0), 0u) << endpoint;

  // A worker joined from the other namespace.
  const auto joined = text.find(" joined; 1 connected");
  const auto pid_at = text.rfind("(pid ", joined);
  const std::string worker_pid = text.substr(pid_at + 5, text.find(')', pid_at) - pid_at - 5);
  struct stat worker_ns {
  }, workers_ns{};
  if (::stat(("/proc/" + worker_pid + "/ns/net").c_str(), &worker_ns) == 0) { // unless it ended already
    ASSERT_EQ(::stat(("/run/netns/" + ns_workers).c_str(), &workers_ns), 0);
    EXPECT_EQ(worker_ns.st_ino, workers_ns.st_ino) << "worker pid " << worker_pid << " is not in " << ns_workers;
  }

  // The keys: this run's, readable by the user alone.
  const std::string keys = out + "/store.keys";
  for (const char* f : {"manager.key", "worker.key"}) {
    const auto perms = fs::status(keys + "/" + f).permissions();
    EXPECT_EQ(perms & (fs::perms::group_all | fs::perms::others_all), fs::perms::none) << f;
  }
  EXPECT_EQ(fs::status(keys).permissions() & (fs::perms::group_all | fs::perms::others_all), fs::perms::none);

  // An intruder with a valid CURVE key pair that is not this run's, and one without CURVE.
  char pub[41] = {}, sec[41] = {};
  ASSERT_EQ(zmq_curve_keypair(pub, sec), 0);
  std::ofstream(dir.file("wrong.key")) << "server " << key_line(keys + "/manager.key", "public") << "\npublic " << pub
                                       << "\nsecret " << sec << "\n";
  pid_t wrong = 0, plain = 0;
  {
    EnvGuard key{"GEOTANDEM_CURVE_KEY_FILE", dir.file("wrong.key")};
    wrong = spawn_in(ns_workers, {test_paths::binary(), "worker", "--connect", endpoint, "--token", "intruder"},
                     dir.file("wrong.log"));
  }
  plain = spawn_in(ns_workers, {test_paths::binary(), "worker", "--connect", endpoint, "--token", "plain"},
                   dir.file("plain.log"));
  EXPECT_TRUE(wait_for_text(log, "is not this run's", manager, 120)) << read_text(log);
  EXPECT_TRUE(wait_for_text(log, "did not use CURVE", manager, 120)) << read_text(log);
  kill(wrong, SIGKILL);
  kill(plain, SIGKILL);
  wait_exit(wrong, 30);
  wait_exit(plain, 30);

  ASSERT_EQ(wait_exit(manager, 600), 0) << read_text(log);
  text = read_text(log);
  EXPECT_NE(text.find("refused a worker connection from " + worker_ip), std::string::npos) << text;
  EXPECT_EQ(text.find("worker intruder"), std::string::npos) << "the intruder must never join:\n" << text;
  expect_same_components(reference + "/store", out + "/store");
}

} // namespace
} // namespace geotandem::testing
