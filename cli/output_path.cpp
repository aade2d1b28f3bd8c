// Default output names after the input.
#include "cli/output_path.h"

#include <filesystem>

namespace strand::cli {

std::string output_from_input(const std::string& input, const std::string& suffix) {
  std::string stem = std::filesystem::path(input).filename().stem().string();
  if (stem.empty() || stem == "." || stem == "..") stem = "strand";
  return stem + suffix;
}

}  // namespace strand::cli
