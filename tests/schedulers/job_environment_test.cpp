// Reading a job's identity from the variables each scheduler sets.
#include <gtest/gtest.h>

#include <map>

#include "geotandem/schedulers/job_environment.hpp"

using namespace geotandem::schedulers;

namespace {
EnvironmentLookup from(std::map<std::string, std::string> values) {
  auto shared = std::make_shared<std::map<std::string, std::string>>(std::move(values));
  return [shared](const char* name) -> const char* {
    auto it = shared->find(name);
    return it == shared->end() ? nullptr : it->second.c_str();
  };
}
} // namespace

TEST(JobEnvironment, LsfArrayElementIsZeroBased) {
  auto id = job_identity_from_environment(from(
      {{"LSB_JOBID", "812"}, {"LSB_JOBINDEX", "3"}, {"LSB_MCPU_HOSTS", "hA 2 hB 1"}, {"GEOTANDEM_LAUNCH_TOKEN", "t"}}));
  EXPECT_EQ(id.backend, "lsf");
  EXPECT_EQ(id.job_id, "812[3]");
  EXPECT_EQ(id.array_index, 2);
  EXPECT_EQ(id.token, "t");
  ASSERT_EQ(id.hosts.size(), 2u);
  EXPECT_EQ(id.hosts[0], (std::pair<std::string, int>{"hA", 2}));
  EXPECT_EQ(id.hosts[1], (std::pair<std::string, int>{"hB", 1}));
}

TEST(JobEnvironment, LsfSingleJobFromLsbHosts) {
  auto id = job_identity_from_environment(from({{"LSB_JOBID", "9"}, {"LSB_JOBINDEX", "0"}, {"LSB_HOSTS", "hA hA hB"}}));
  EXPECT_EQ(id.job_id, "9");
  EXPECT_EQ(id.array_index, 0);
  ASSERT_EQ(id.hosts.size(), 2u);
  EXPECT_EQ(id.hosts[0].second, 2);
}

TEST(JobEnvironment, SlurmArrayAndLocal) {
  auto slurm = job_identity_from_environment(from({{"SLURM_JOB_ID", "57"},
                                                   {"SLURM_ARRAY_JOB_ID", "55"},
                                                   {"SLURM_ARRAY_TASK_ID", "2"},
                                                   {"SLURM_JOB_NODELIST", "n[1-2]"}}));
  EXPECT_EQ(slurm.backend, "slurm");
  EXPECT_EQ(slurm.job_id, "55_2");
  EXPECT_EQ(slurm.array_index, 2);
  auto local = job_identity_from_environment(from({{"GEOTANDEM_JOB_ID", "local-4"}, {"GEOTANDEM_ARRAY_INDEX", "1"}}));
  EXPECT_EQ(local.backend, "local");
  EXPECT_EQ(local.array_index, 1);
  EXPECT_EQ(job_identity_from_environment(from({})).backend, "");
}
