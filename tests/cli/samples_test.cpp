// samples/: every generator has an example job, and every job and sweep there runs.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>

#include "machines/profile.h"
#include "patterns/registry.h"
#include "tests/support/cli_runner.h"
#include "tests/support/sample_jobs.h"

namespace strand::testing {
namespace {

const std::string kSamples = samples_dir();

TEST(Samples, EveryGeneratorHasAnExampleJob) {
  std::set<std::string> covered;
  for (const auto& f : json_files(kSamples)) {
    covered.insert(nlohmann::json::parse(slurp(f.string())).value("generator", ""));
  }
  for (const auto& g : patterns::generators()) EXPECT_TRUE(covered.count(g.name)) << "no samples/*.json for " << g.name;
}

// A robot cell writes a pose CSV (with its programs beside it), other machines G-code.
std::string output_for(const nlohmann::json& job) {
  return machines::load_profile(job.value("machine", "deltawasp-2040-clay")).robot.enabled
             ? "out.csv"
             : "out.gcode";
}

TEST(Samples, EveryJobRuns) {
  for (const auto& f : json_files(kSamples)) {
    const auto dir = fresh_dir("sample-job");
    const auto r = run_strand(
        "job '" + f.string() + "' -o " + output_for(nlohmann::json::parse(slurp(f.string()))), dir);
    EXPECT_EQ(r.exit_code, 0) << f << ": " << r.err;
  }
}

TEST(Samples, EverySweepRunsWithoutFailures) {
  for (const auto& f : json_files(kSamples + "/sweeps")) {
    const auto dir = fresh_dir("sample-sweep");
    const auto r = run_strand("sweep '" + f.string() + "' -o out --no-previews", dir);
    EXPECT_EQ(r.exit_code, 0) << f << ": " << r.err;
  }
}

}  // namespace
}  // namespace strand::testing
