// The forward-only rule and the replacement policy.
#include <gtest/gtest.h>

#include "geotandem/schedulers/job_state.hpp"
#include "geotandem/schedulers/replacement_policy.hpp"
#include "geotandem/schedulers/scheduler_error.hpp"

using namespace geotandem::schedulers;

namespace {
JobStatus status(JobState state, std::string host = {}) {
  JobStatus s;
  s.state = state;
  s.host = std::move(host);
  return s;
}
} // namespace

TEST(JobState, MovesForwardOnly) {
  JobStatus s = status(JobState::pending);
  s = advance(s, status(JobState::running, "n1"));
  EXPECT_EQ(s.state, JobState::running);
  s = advance(s, status(JobState::pending)); // a requeue we did not ask for
  EXPECT_EQ(s.state, JobState::running);
  EXPECT_EQ(s.host, "n1");
  JobStatus failed = status(JobState::failed);
  failed.exit_code = 3;
  s = advance(s, failed);
  EXPECT_EQ(s.state, JobState::failed);
  EXPECT_EQ(s.exit_code, 3);
  EXPECT_EQ(s.host, "n1") << "where it ran is still known";
  for (JobState later : {JobState::pending, JobState::running, JobState::completed, JobState::vanished}) {
    EXPECT_EQ(advance(s, status(later)).state, JobState::failed) << to_string(later);
  }
}

TEST(JobState, PendingCanJumpStraightToAnyEnd) {
  for (JobState end : {JobState::completed, JobState::failed, JobState::cancelled, JobState::timed_out,
                       JobState::node_failure, JobState::vanished}) {
    EXPECT_TRUE(is_terminal(end));
    EXPECT_EQ(advance(status(JobState::pending), status(end)).state, end);
  }
  EXPECT_FALSE(is_terminal(JobState::pending));
  EXPECT_FALSE(is_terminal(JobState::running));
}

TEST(JobState, SameTerminalStateFillsMissingDetails) {
  JobStatus first = status(JobState::failed);
  JobStatus later = status(JobState::failed, "n2");
  later.exit_code = 7;
  JobStatus merged = advance(first, later);
  EXPECT_EQ(merged.exit_code, 7);
  EXPECT_EQ(merged.host, "n2");
}

TEST(ReplacementPolicy, ReplacesLostOrKilledJobsUpToTheLimit) {
  ReplacementPolicy policy(2);
  JobStatus killed = status(JobState::failed);
  killed.signal = 9;
  EXPECT_TRUE(ReplacementPolicy::wants_replacement(killed));
  EXPECT_TRUE(ReplacementPolicy::wants_replacement(status(JobState::vanished)));
  EXPECT_TRUE(ReplacementPolicy::wants_replacement(status(JobState::node_failure)));
  EXPECT_TRUE(ReplacementPolicy::wants_replacement(status(JobState::cancelled)));
  EXPECT_TRUE(ReplacementPolicy::wants_replacement(status(JobState::timed_out)));
  JobStatus exited = status(JobState::failed);
  exited.exit_code = 3;
  EXPECT_FALSE(ReplacementPolicy::wants_replacement(exited)) << "a worker that fails by itself would fail again";
  EXPECT_FALSE(ReplacementPolicy::wants_replacement(status(JobState::completed)));
  EXPECT_FALSE(ReplacementPolicy::wants_replacement(status(JobState::running)));

  policy.record("slurm", "41", status(JobState::vanished));
  policy.record("slurm", "42", killed);
  EXPECT_EQ(policy.used(), 2);
  try {
    policy.record("slurm", "43", status(JobState::node_failure, "n7"));
    FAIL() << "the third replacement is past the limit";
  } catch (const SchedulerError& error) {
    std::string what = error.what();
    EXPECT_NE(what.find("slurm"), std::string::npos) << what;
    EXPECT_NE(what.find("43"), std::string::npos) << what;
    EXPECT_NE(what.find("node_failure"), std::string::npos) << what;
    EXPECT_NE(what.find("n7"), std::string::npos) << what;
    EXPECT_NE(what.find("limit"), std::string::npos) << what;
  }
  EXPECT_THROW(policy.record("slurm", "44", exited), geotandem::InvalidArgument);
  EXPECT_THROW(ReplacementPolicy(-1), geotandem::InvalidArgument);
}
