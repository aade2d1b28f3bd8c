// samples/: every generator has an example job, and every job and sweep there runs.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>

#include "patterns/registry.h"
#include "tests/support/cli_runner.h"

namespace strand::testing {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> json_files(const std::string& dir) {
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.is_regular_file() && e.path().extension() == ".json") files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

const std::string kSamples = std::string(STRAND_SOURCE_DIR) + "/samples";

TEST(Samples, EveryGeneratorHasAnExampleJob) {
  std::set<std::string> covered;
  for (const auto& f : json_files(kSamples)) {
    covered.insert(nlohmann::json::parse(slurp(f.string())).value("generator", ""));
  }
  for (const auto& g : patterns::generators()) EXPECT_TRUE(covered.count(g.name)) << "no samples/*.json for " << g.name;
}

TEST(Samples, EveryJobRuns) {
  for (const auto& f : json_files(kSamples)) {
    const auto dir = fresh_dir("sample-job");
    const auto r = run_strand("job '" + f.string() + "' -o out.gcode", dir);
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
