// Reads samples/*.json once per test program.
#include "tests/support/sample_jobs.h"

#include <algorithm>

#include "tests/support/cli_runner.h"

namespace strand::testing {

namespace fs = std::filesystem;

std::string samples_dir() { return std::string(STRAND_SOURCE_DIR) + "/samples"; }

std::vector<fs::path> json_files(const std::string& dir) {
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.is_regular_file() && e.path().extension() == ".json") files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

const std::map<std::string, nlohmann::json>& sample_params() {
  static const std::map<std::string, nlohmann::json> kParams = [] {
    std::map<std::string, nlohmann::json> params;
    for (const auto& f : json_files(samples_dir())) {
      const auto job = nlohmann::json::parse(slurp(f.string()));
      if (job.contains("substrate")) continue;  // curved jobs: their own tests
      params.emplace(job.value("generator", ""), job.value("params", nlohmann::json::object()));
    }
    return params;
  }();
  return kParams;
}

}  // namespace strand::testing
