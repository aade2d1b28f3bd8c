// Sweep progress on stderr: a redrawn bar with counts and ETA on a terminal, one plain line
// per finished point otherwise (logs of cluster jobs).
#pragma once

#include <chrono>
#include <cstddef>
#include <ostream>
#include <string>

namespace strand::cli {

class ProgressBar {
 public:
  ProgressBar(std::ostream& out, bool terminal);
  // `name` and `status` describe the point just finished; a status starting with "failed"
  // is also printed on its own line on a terminal.
  void update(std::size_t done, std::size_t total, std::size_t failed, const std::string& name,
              const std::string& status);
  void finish();

 private:
  std::ostream& out_;
  bool terminal_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_;
};

// "1:05", "12:00:03": seconds as a clock for ETAs.
std::string clock_text(double seconds);

}  // namespace strand::cli
