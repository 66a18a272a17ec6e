// `geotandem run-workflow --scheduler slurm` on the three-node test cluster of the slurm_nodes
// fixture (scripts/slurm-test-cluster.sh start DIR 3): slurmctld and the manager on a bridge in
// this network namespace, each node's slurmd (and so its jobs) in a namespace of its own with its
// own address, one munge key, one filesystem. The manager binds the controller's address (CURVE
// on); its worker jobs run on the three nodes and give the components of the in-process run. A
// node that dies mid-run (every process in its namespace SIGKILLed) loses nothing, and a job that
// starts late (its node drained, then resumed during the run) joins and gets work at once.
#include <sys/stat.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>

#include "cluster_run.hpp"

namespace geotandem::testing {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

std::string output_of(const std::string& command) {
  std::string text;
  if (FILE* f = popen((command + " 2>&1").c_str(), "r")) {
    char buffer[512];
    while (std::fgets(buffer, sizeof buffer, f))
      text += buffer;
    pclose(f);
  }
  while (!text.empty() && (text.back() == '\n' || text.back() == ' '))
    text.pop_back();
  return text;
}

int sh(const std::string& command) {
  const int status = std::system((command + " >/dev/null 2>&1").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// The node Slurm ran (or runs) a job on: squeue's NodeList, which finished jobs keep for MinJobAge.
std::string node_of_job(const std::string& job) {
  return output_of("squeue -h -t all -j " + job + " -o %N");
}

// The network namespace (its inode) a process is in; 0 when the process is gone.
ino_t net_namespace(const std::string& path) {
  struct stat s {};
  return ::stat(path.c_str(), &s) == 0 ? s.st_ino : 0;
}

// "worker T (pid N) joined" lines: token to pid, in the order they joined.
std::vector<std::pair<std::string, std::string>> joined_workers(const std::string& log) {
  std::vector<std::pair<std::string, std::string>> out;
  static const std::regex re("worker ([^ ]+) \\(pid ([0-9]+)\\) joined; ");
  for (auto it = std::sregex_iterator(log.begin(), log.end(), re); it != std::sregex_iterator(); ++it)
    out.emplace_back((*it)[1], (*it)[2]);
  return out;
}

// "slurm: worker T submitted as job J": the job of a token.
std::string job_of(const std::string& log, const std::string& token) {
  std::smatch m;
  return std::regex_search(log, m, std::regex("worker " + token + " submitted as job ([^ ]+) ")) ? m[1].str()
                                                                                                 : std::string();
}

// The log's lines about jobs and workers coming and going (not the debug lines of each task), for
// the test's output.
std::string story(const std::string& log) {
  std::istringstream in(log);
  std::string line, out;
  while (std::getline(in, line))
    if (line.find("debug:") == std::string::npos &&
        (line.find("worker") != std::string::npos || line.find("job") != std::string::npos))
      out += line + "\n";
  return out;
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1))
    ++n;
  return n;
}

// The cluster written by the start script: the controller's address, each node's namespace.
struct Cluster {
  std::string dir, script, controller;
  std::map<std::string, std::string> namespace_of; // node name -> network namespace

  static Cluster read() {
    Cluster c;
    // The cluster's directory holds its slurm.conf.
    const char* conf = std::getenv("SLURM_CONF");
    if (!conf || !fs::exists(fs::path(conf).parent_path() / "cluster.env")) return c;
    c.dir = fs::path(conf).parent_path().string();
    c.script = test_paths::source() + "/scripts/slurm-test-cluster.sh";
    // cluster.env is bash: `SLURM_TEST_CONTROLLER=A`, `node_names=(n1 n2 n3 )`, `node_ns=('' a b c )`.
    const std::string names = output_of("bash -c '. " + c.dir + "/cluster.env && echo ${node_names[*]}'");
    const std::string spaces = output_of("bash -c '. " + c.dir + "/cluster.env && echo ${node_ns[*]}'");
    c.controller = output_of("bash -c '. " + c.dir + "/cluster.env && echo $SLURM_TEST_CONTROLLER'");
    std::istringstream n(names), s(spaces);
    std::string name, ns;
    while (n >> name && s >> ns)
      c.namespace_of[name] = ns;
    return c;
  }
};

struct SlurmNodes : ::testing::Test {
  ScratchDir dir;
  Cluster cluster = Cluster::read();
  std::string shape = "[96,96,64]";
  std::string reference = dir.file("local");

  void SetUp() override {
    ASSERT_NE(std::getenv("SLURM_CONF"), nullptr) << "run through ctest (the slurm_nodes fixture sets SLURM_CONF)";
    ASSERT_FALSE(cluster.dir.empty()) << "SLURM_CONF is not a multi-node test cluster's (no cluster.env beside it)";
    ASSERT_EQ(cluster.namespace_of.size(), 3u) << "cluster.env of " << cluster.dir;
    ASSERT_FALSE(cluster.controller.empty());
    // All three nodes idle: an earlier test that failed half-way may have left one down or drained.
    for (const auto& [node, ns] : cluster.namespace_of) {
      sh("scontrol update NodeName=" + node + " State=RESUME");
      ASSERT_EQ(sh(cluster.script + " start-node " + cluster.dir + " " + node), 0) << node << " is not idle";
    }
  }

  void make_reference() {
    auto args = cluster_args(reference, "local", 1, shape);
    ASSERT_EQ(run_geotandem("-q" + shell_args(args)).exit_code, 0);
  }

  // Three worker jobs of 2 CPUs each (a node's all), the manager on the controller's address, the
  // task assignments logged (debug).
  std::vector<std::string> slurm_args(const std::string& out, int workers = 3) const {
    auto args = cluster_args(out, "slurm", workers, shape);
    args[1] = "debug";
    args.insert(args.end(), {"--bind", cluster.controller, "--set", "execution.resources.cpus_per_worker=2"});
    return args;
  }
};

TEST_F(SlurmNodes, WorkerJobsRunOnThreeNodesAndGiveTheComponentsOfTheInProcessRun) {
  make_reference();
  const std::string out = dir.file("slurm"), log = dir.file("manager.log");
  const pid_t manager = spawn_geotandem(slurm_args(out), log);
  ASSERT_TRUE(wait_for_text(log, "joined; 3 connected", manager, 300)) << read_text(log);
  std::string text = read_text(log);
  EXPECT_NE(text.find("CurveZMQ is on"), std::string::npos) << text;
  EXPECT_NE(text.find("manager listening on tcp://" + cluster.controller + ":"), std::string::npos) << text;

  // Each worker, while it runs, is in the namespace of the node Slurm says its job is on: the
  // kernel's account and Slurm's agree, and the three are on three nodes.
  std::set<std::string> nodes;
  for (const auto& [token, pid] : joined_workers(text)) {
    const std::string job = job_of(text, token);
    ASSERT_FALSE(job.empty()) << token << "\n" << text;
    const std::string node = node_of_job(job);
    ASSERT_TRUE(cluster.namespace_of.count(node)) << "job " << job << " on '" << node << "'";
    nodes.insert(node);
    std::cout << "worker " << token << " (pid " << pid << "): job " << job << " on " << node << "\n";
    const ino_t worker_ns = net_namespace("/proc/" + pid + "/ns/net");
    if (worker_ns == 0) continue; // it ended already
    EXPECT_EQ(worker_ns, net_namespace("/run/netns/" + cluster.namespace_of.at(node)))
        << "worker " << token << " (pid " << pid << ", job " << job << ") is not in " << node << "'s namespace";
    EXPECT_NE(worker_ns, net_namespace("/proc/self/ns/net")) << "worker " << token << " runs beside the manager";
  }
  EXPECT_EQ(nodes, (std::set<std::string>{"node1", "node2", "node3"})) << text;

  ASSERT_EQ(wait_exit(manager, 600), 0) << read_text(log);
  text = read_text(log);
  EXPECT_EQ(submitted_jobs(text).size(), 3u) << text;
  EXPECT_EQ(text.find("re-done"), std::string::npos) << text;
  // Every worker did work, and each job's output is in the shared output directory.
  EXPECT_EQ(count(text, " done after "), 3u) << text;
  EXPECT_EQ(count(text, " done after 0 task(s)"), 0u) << text;
  for (const std::string& id : submitted_jobs(text))
    EXPECT_TRUE(fs::exists(out + "/worker-logs/" + id + ".log")) << id;
  expect_same_components(reference + "/store", out + "/store"); // throws on a key committed twice
}

TEST_F(SlurmNodes, ANodeThatDiesMidRunLosesNothing) {
  shape = "[128,128,80]"; // long enough that the node dies with work left
  make_reference();
  const std::string out = dir.file("slurm"), log = dir.file("manager.log");
  const pid_t manager = spawn_geotandem(slurm_args(out), log);
  ASSERT_TRUE(wait_for_text(log, "joined; 3 connected", manager, 300)) << read_text(log);
  // The worker on node2, once it has a task.
  std::string text = read_text(log), token, job;
  for (const auto& [t, pid] : joined_workers(text))
    if (node_of_job(job_of(text, t)) == "node2") token = t, job = job_of(text, t);
  ASSERT_FALSE(token.empty()) << "no worker job on node2:\n" << text;
  ASSERT_TRUE(wait_for_text(log, "worker " + token + ": EXTRACT of ", manager, 120)) << read_text(log);
  std::this_thread::sleep_for(std::chrono::seconds(1));
  ASSERT_FALSE(read_text(log).find(" done after ") != std::string::npos) << "the run ended before the node died";

  const auto died = Clock::now();
  ASSERT_EQ(sh(cluster.script + " kill-node " + cluster.dir + " node2"), 0);
  ASSERT_TRUE(wait_for_text(log, "worker " + token + " (pid", manager, 120));
  ASSERT_EQ(wait_exit(manager, 900), 0) << read_text(log);
  const double seconds = std::chrono::duration<double>(Clock::now() - died).count();
  text = read_text(log);
  // The manager saw the worker go (silent, or its job failed with the node) and had its blocks re-done.
  std::smatch lost;
  ASSERT_TRUE(std::regex_search(
      text, lost, std::regex("worker " + token + " \\(pid [0-9]+\\) [^\n]*: ([0-9]+) block\\(s\\) will be re-done")))
      << text;
  EXPECT_EQ(text.find("worker " + token + " done after"), std::string::npos) << text;
  // The other two finished the run.
  EXPECT_GE(count(text, " done after "), 2u) << text;
  expect_same_components(reference + "/store", out + "/store"); // throws on a key committed twice
  RecordProperty("seconds_after_the_node_died", std::to_string(seconds));
  std::cout << "the run completed " << seconds << " s after node2 died; the worker's " << lost[1]
            << " block(s) re-done elsewhere; job " << job << " is "
            << output_of("squeue -h -t all -j " + job + " -o %T") << "\n"
            << story(text);
}

TEST_F(SlurmNodes, AJobThatStartsLateJoinsAndGetsWorkAtOnce) {
  // The run must outlast a job's start on a resumed node (seconds in slurmctld's scheduling
  // cycle): one leaf per EXTRACT (no batches) on a cube whose run takes tens of seconds here, where
  // batches and dropped empty surfaces (issue 55) finished 128x128x80 before the late job started.
  shape = "[160,160,96]";
  make_reference();
  struct NoBatches {
    NoBatches() { setenv("GEOTANDEM_EXTRACT_BATCH", "1", 1); }
    ~NoBatches() { unsetenv("GEOTANDEM_EXTRACT_BATCH"); }
  } no_batches;
  struct Resume {
    ~Resume() { sh("scontrol update NodeName=node3 State=RESUME"); }
  } resume;
  ASSERT_EQ(sh("scontrol update NodeName=node3 State=DRAIN Reason=geotandem-test-late-start"), 0);
  const std::string out = dir.file("slurm"), log = dir.file("manager.log");
  const pid_t manager = spawn_geotandem(slurm_args(out), log);
  ASSERT_TRUE(wait_for_text(log, "joined; 2 connected", manager, 300)) << read_text(log);
  std::string text = read_text(log);
  ASSERT_EQ(submitted_jobs(text).size(), 3u) << text;
  const std::string late_job = submitted_jobs(text)[2];
  ASSERT_TRUE(job_of(text, joined_workers(text)[0].first) != late_job &&
              job_of(text, joined_workers(text)[1].first) != late_job)
      << text;
  EXPECT_EQ(output_of("squeue -h -j " + late_job + " -o %T"), "PENDING");
  // The run is under way with two workers; then node3 is freed.
  for (int i = 0; i < 600 && count(read_text(log), ": EXTRACT of ") < 4; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  ASSERT_EQ(sh("scontrol update NodeName=node3 State=RESUME"), 0);
  ASSERT_TRUE(wait_for_text(log, "joined; 3 connected", manager, 300)) << read_text(log);
  const auto joined = Clock::now();
  text = read_text(log);
  const std::string late = joined_workers(text).back().first;
  EXPECT_EQ(job_of(text, late), late_job);
  ASSERT_EQ(text.find(" done after "), std::string::npos) << "the run ended before the late job joined:\n" << text;
  ASSERT_TRUE(wait_for_text(log, "worker " + late + ": EXTRACT of ", manager, 60)) << read_text(log);
  const double wait = std::chrono::duration<double>(Clock::now() - joined).count();
  EXPECT_LT(wait, 2.0) << "the late worker waited " << wait << " s for its first task";
  EXPECT_EQ(node_of_job(late_job), "node3");

  ASSERT_EQ(wait_exit(manager, 900), 0) << read_text(log);
  text = read_text(log);
  EXPECT_EQ(text.find("re-done"), std::string::npos) << text;
  std::smatch done;
  ASSERT_TRUE(std::regex_search(text, done, std::regex("worker " + late + " done after ([0-9]+) task")));
  EXPECT_GE(std::stoi(done[1]), 1) << text;
  expect_same_components(reference + "/store", out + "/store");
  std::cout << "the late worker got its first task " << wait << " s after it joined; it did " << done[1] << " task(s)\n"
            << story(text);
}

} // namespace
} // namespace geotandem::testing
