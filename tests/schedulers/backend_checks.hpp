#pragma once
// The same end-to-end checks for every backend (local, the LSF stand-ins, the real Slurm): real
// jobs, real output files, real cancellation. Each check submits through the Scheduler interface
// only and waits with a JobWatcher (short interval, generous bound).

#include <gtest/gtest.h>

#include <filesystem>
#include <set>

#include "geotandem/schedulers/job_watcher.hpp"
#include "geotandem/schedulers/scheduler.hpp"
#include "scheduler_fixtures.hpp"

namespace geotandem::testing {

inline schedulers::WatchOptions quick_watch() {
  return {std::chrono::milliseconds(200)};
}
constexpr std::chrono::seconds job_bound{180};

inline schedulers::LaunchRequest shell_job(const std::filesystem::path& dir, const std::string& script) {
  schedulers::LaunchRequest r;
  r.argv = {"/bin/sh", "-c", script};
  r.workdir = dir.string();
  r.stdout_path = (dir / "job-{job}-{index}.out").string();
  r.stderr_path = (dir / "job-{job}-{index}.err").string();
  r.name = "gt-test";
  return r;
}

// Files in dir whose name starts with prefix.
inline std::vector<std::filesystem::path> files_starting(const std::filesystem::path& dir, const std::string& prefix) {
  std::vector<std::filesystem::path> found;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    if (entry.path().filename().string().rfind(prefix, 0) == 0) found.push_back(entry.path());
  return found;
}

inline void check_job_completes_with_env_and_output(schedulers::Scheduler& scheduler,
                                                    const std::filesystem::path& dir) {
  auto r = shell_job(dir, "echo \"token=$GEOTANDEM_LAUNCH_TOKEN extra=$EXTRA pwd=$(pwd -P)\"; echo oops >&2");
  r.token = "tok-42";
  r.env = {{"EXTRA", "it's here"}};
  r.stdout_path = (dir / "done.out").string();
  r.stderr_path = (dir / "done.err").string();
  auto ids = scheduler.submit(r);
  ASSERT_EQ(ids.size(), 1u);
  schedulers::JobWatcher watcher(scheduler, quick_watch());
  auto statuses = watcher.wait_all(ids, CancelToken{}, job_bound);
  EXPECT_EQ(statuses[ids[0]].state, schedulers::JobState::completed) << statuses[ids[0]].reason;
  // The scheduler may write output after the state changes (LSF copies it at the end).
  ASSERT_TRUE(eventually([&] { return !read_text(dir / "done.out").empty(); }, std::chrono::seconds(30)));
  EXPECT_EQ(read_text(dir / "done.out"),
            "token=tok-42 extra=it's here pwd=" + std::filesystem::canonical(dir).string() + "\n");
  EXPECT_EQ(read_text(dir / "done.err"), "oops\n");
}

inline void check_job_fails_with_exit_code(schedulers::Scheduler& scheduler, const std::filesystem::path& dir) {
  auto ids = scheduler.submit(shell_job(dir, "exit 3"));
  schedulers::JobWatcher watcher(scheduler, quick_watch());
  auto status = watcher.wait_all(ids, CancelToken{}, job_bound)[ids[0]];
  EXPECT_EQ(status.state, schedulers::JobState::failed);
  EXPECT_EQ(status.exit_code, 3);
  EXPECT_FALSE(status.host.empty());
}

inline void check_cancel_mid_run(schedulers::Scheduler& scheduler, const std::filesystem::path& dir) {
  auto r = shell_job(dir, "echo started; exec sleep 600");
  r.stdout_path = (dir / "cancel.out").string();
  auto ids = scheduler.submit(r);
  schedulers::JobWatcher watcher(scheduler, quick_watch());
  ASSERT_TRUE(
      eventually([&] { return watcher.statuses(ids)[ids[0]].state == schedulers::JobState::running; }, job_bound));
  ASSERT_TRUE(eventually([&] { return read_text(dir / "cancel.out") == "started\n"; }, std::chrono::seconds(60)));
  const auto start = std::chrono::steady_clock::now();
  scheduler.cancel(ids);
  scheduler.cancel(ids); // idempotent
  auto status = watcher.wait_all(ids, CancelToken{}, job_bound)[ids[0]];
  EXPECT_EQ(status.state, schedulers::JobState::cancelled);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(120)) << "the 600 s sleep was ended";
  EXPECT_NO_THROW(scheduler.cancel(ids)) << "cancelling a finished job is harmless";
}

inline void check_array(schedulers::Scheduler& scheduler, const std::filesystem::path& dir) {
  auto r = shell_job(dir, "echo \"element of $GEOTANDEM_LAUNCH_TOKEN\"");
  r.token = "arr";
  r.array_size = 3;
  r.stdout_path = (dir / "arr-{index}.out").string();
  r.stderr_path = "";
  auto ids = scheduler.submit(r);
  ASSERT_EQ(ids.size(), 3u);
  EXPECT_EQ(std::set<std::string>(ids.begin(), ids.end()).size(), 3u) << "distinct ids";
  schedulers::JobWatcher watcher(scheduler, quick_watch());
  auto statuses = watcher.wait_all(ids, CancelToken{}, job_bound);
  EXPECT_EQ(watcher.polls() >= 1, true);
  for (const auto& id : ids)
    EXPECT_EQ(statuses[id].state, schedulers::JobState::completed) << id;
  ASSERT_TRUE(eventually([&] { return files_starting(dir, "arr-").size() == 3; }, std::chrono::seconds(30)));
  for (const auto& file : files_starting(dir, "arr-")) {
    ASSERT_TRUE(eventually([&] { return !read_text(file).empty(); }, std::chrono::seconds(30)));
    EXPECT_EQ(read_text(file), "element of arr\n") << file;
  }
}

inline void check_poll_many_and_unknown(schedulers::Scheduler& scheduler, const std::filesystem::path& dir) {
  std::vector<schedulers::JobId> ids;
  for (int i = 0; i < 4; ++i) {
    auto one = scheduler.submit(shell_job(dir, "exit " + std::to_string(i)));
    ids.insert(ids.end(), one.begin(), one.end());
  }
  schedulers::JobWatcher watcher(scheduler, quick_watch());
  auto statuses = watcher.wait_all(ids, CancelToken{}, job_bound);
  ASSERT_EQ(statuses.size(), 4u);
  EXPECT_EQ(statuses[ids[0]].state, schedulers::JobState::completed);
  for (int i = 1; i < 4; ++i)
    EXPECT_EQ(statuses[ids[i]].exit_code, i) << ids[i];
  auto with_stranger = ids;
  with_stranger.push_back("999999");
  auto again = scheduler.poll(with_stranger);
  EXPECT_EQ(again["999999"].state, schedulers::JobState::vanished);
  EXPECT_EQ(again[ids[2]].exit_code, 2) << "finished states are kept";
}

} // namespace geotandem::testing
