// InputError: a problem the user can fix (bad parameter, unknown machine, part too big).
// Its message is one line meant to be printed as is; main() maps it to exit code 2.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace strand {

class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
  // Joins several problems ("a = 1: must be > 2 (mm)") into one line separated by "; ".
  explicit InputError(const std::vector<std::string>& problems)
      : std::runtime_error(join(problems)) {}

 private:
  static std::string join(const std::vector<std::string>& problems) {
    std::string out;
    for (const auto& p : problems) {
      if (!out.empty()) out += "; ";
      out += p;
    }
    return out;
  }
};

}  // namespace strand
