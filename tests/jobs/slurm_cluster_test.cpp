// `strand sweep --slurm` on a real Slurm (tests/support/slurm_cluster.h starts one as root):
// a 24-point sweep in 4 array tasks merged into the manifest a local run writes, byte for
// byte; and a task cancelled mid-run, resumed with --resume, merged to the same bytes.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <regex>
#include <thread>

#include "jobs/sweep_journal.h"
#include "tests/support/cli_runner.h"
#include "tests/support/slurm_cluster.h"

namespace strand::testing {
namespace {

namespace fs = std::filesystem;

// 24 points: 3 gaps x 8 nozzles. `size` sets how long each point takes.
std::string sweep_file(const std::string& size, int height) {
  return R"({"job": {"generator": "scaffold", "params": {"size": ")" + size + R"(", "height": )" +
         std::to_string(height) + R"(}}, "vary": {"gap": [1.2, 1.4, 1.6], "nozzle": {"from": 0.4, "to": 0.75, "step": 0.05}}})";
}

struct Jobs {
  std::string array, merge;
};

Jobs job_ids(const std::string& out) {
  std::smatch m;
  if (!std::regex_search(out, m, std::regex("array job ([0-9]+) .*merge job ([0-9]+)"))) return {};
  return {m[1].str(), m[2].str()};
}

class SlurmClusterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string why = SlurmCluster::why_not();
    if (!why.empty()) GTEST_SKIP() << "no Slurm cluster: " << why;
    cluster_ = std::make_unique<SlurmCluster>();
    ASSERT_EQ(cluster_->error(), "");
    dir_ = fresh_dir("slurm-sweep");
  }

  // The same sweep run locally, unsharded: what the cluster's merge must reproduce.
  void expect_same_as_local(const std::string& flags) {
    ASSERT_EQ(run_strand("sweep s.json -o local " + flags, dir_).exit_code, 0);
    EXPECT_EQ(slurp(dir_ + "/cluster/manifest.json"), slurp(dir_ + "/local/manifest.json"));
    EXPECT_EQ(slurp(dir_ + "/cluster/manifest.csv"), slurp(dir_ + "/local/manifest.csv"));
    std::size_t gcodes = 0;
    for (const auto& e : fs::directory_iterator(dir_ + "/local")) {
      if (e.path().extension() != ".gcode") continue;
      ++gcodes;
      EXPECT_EQ(slurp(dir_ + "/cluster/" + e.path().filename().string()), slurp(e.path().string())) << e.path();
    }
    EXPECT_EQ(gcodes, 24u);
  }

  std::unique_ptr<SlurmCluster> cluster_;
  std::string dir_;
};

TEST_F(SlurmClusterTest, FourArrayTasksMergeToTheManifestOfALocalRun) {
  std::ofstream(dir_ + "/s.json") << sweep_file("10x10", 1);
  const auto r = run_strand("sweep s.json -o cluster --slurm --tasks 4 --no-previews", dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Jobs jobs = job_ids(r.out);
  ASSERT_FALSE(jobs.merge.empty()) << r.out;
  ASSERT_TRUE(cluster_->wait_for(jobs.merge, 120)) << cluster_->logs();
  const std::string merge_log = slurp(dir_ + "/cluster/slurm/merge.log");
  EXPECT_NE(merge_log.find("sweep: merged 4 shard(s), 24 point(s)"), std::string::npos) << merge_log;
  for (int task = 1; task <= 4; ++task) {
    const std::string log = slurp(dir_ + "/cluster/slurm/task-" + std::to_string(task) + ".log");
    EXPECT_NE(log.find("sweep: 6 point(s): 6 ran, 0 up to date"), std::string::npos) << log;
  }
  expect_same_as_local("--no-previews");
  const auto status = run_strand("sweep --status -o cluster", dir_);
  EXPECT_NE(status.out.find("24 point(s) in 4 shard(s): 24 done, 0 running, 0 failed, 0 waiting, merged"),
            std::string::npos) << status.out;
}

TEST_F(SlurmClusterTest, ACancelledTaskIsResumedAndMergesToTheSameBytes) {
  // Points of about 0.3 s with their previews, so task 2 can be caught between its first
  // journalled point and its last (1.5 s later).
  std::ofstream(dir_ + "/s.json") << sweep_file("120x120", 300);
  const auto r = run_strand("sweep s.json -o cluster --slurm --tasks 4", dir_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Jobs first = job_ids(r.out);
  ASSERT_FALSE(first.merge.empty()) << r.out;
  const std::string journal = dir_ + "/cluster/manifest-shard-2-of-4.journal.jsonl";
  bool caught = false;
  for (int i = 0; i < 3000 && !caught; ++i) {
    caught = jobs::journal_rows(journal).size() >= 1;
    if (!caught) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_TRUE(caught) << "task 2 journalled no point within 60 s" << cluster_->logs();
  cluster_->shell_out("scancel " + first.array + "_2");
  ASSERT_TRUE(cluster_->wait_for(first.merge, 120)) << cluster_->logs();
  ASSERT_FALSE(exists(dir_ + "/cluster/manifest-shard-2-of-4.json")) << "task 2 finished before it was cancelled";
  EXPECT_FALSE(exists(dir_ + "/cluster/manifest.json"));
  // The merge ran (afterany) and named the task that did not finish and its log.
  const std::string merge_log = slurp(dir_ + "/cluster/slurm/merge.log");
  EXPECT_NE(merge_log.find("1 of 4 shards did not finish: shard 2/4 (array task 2, log " + dir_ +
                           "/cluster/slurm/task-2.log"), std::string::npos) << merge_log;
  const std::size_t kept = jobs::journal_rows(journal).size();
  ASSERT_GE(kept, 1u);
  ASSERT_LT(kept, 6u);
  const auto status = run_strand("sweep --status -o cluster", dir_);
  EXPECT_NE(status.out.find("shard 2/4: 6 point(s), " + std::to_string(kept) + " done, 0 running, 0 failed (stopped)"),
            std::string::npos) << status.out;

  const auto resumed = run_strand("sweep s.json -o cluster --slurm --resume", dir_);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_NE(resumed.out.find("(tasks 2)"), std::string::npos) << resumed.out;
  const Jobs second = job_ids(resumed.out);
  ASSERT_TRUE(cluster_->wait_for(second.merge, 120)) << cluster_->logs();
  // Task 2's second run reused the points its first run journalled.
  const std::string log = slurp(dir_ + "/cluster/slurm/task-2.log");
  EXPECT_NE(log.find("sweep: 6 point(s): " + std::to_string(6 - kept) + " ran, " + std::to_string(kept) + " up to date"),
            std::string::npos) << log;
  expect_same_as_local("");
  for (const auto& e : fs::directory_iterator(dir_ + "/local/previews")) {
    EXPECT_EQ(slurp(dir_ + "/cluster/previews/" + e.path().filename().string()), slurp(e.path().string())) << e.path();
  }
}

}  // namespace
}  // namespace strand::testing
