// The example jobs in samples/: tests take their parameter sets from there instead of
// keeping private copies, so a sample that stops working fails the tests that use it.
#pragma once

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace strand::testing {

// samples/ in the source tree.
std::string samples_dir();
// The .json files directly in `dir`, sorted by name.
std::vector<std::filesystem::path> json_files(const std::string& dir);
// Generator name -> the "params" of its first flat sample job (by file name) in samples/;
// jobs on a curved substrate are left out.
const std::map<std::string, nlohmann::json>& sample_params();

}  // namespace strand::testing
