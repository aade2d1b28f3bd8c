// Shell-based runner for the strand binary (tests only).
#include "tests/support/cli_runner.h"

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <unistd.h>

namespace strand::testing {

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

namespace {

// stderr without the plain progress lines a run prints once it has taken a second (a loaded or
// sanitizer-built machine): "trace: 2/3 tracing (1.0 s)". They are not part of the error.
std::string without_progress(const std::string& err) {
  static const std::regex progress(R"([a-z-]+: \d+/\d+ .* \(\d+(\.\d+)? s\))");
  std::istringstream in(err);
  std::string line, kept;
  while (std::getline(in, line))
    if (!std::regex_match(line, progress)) kept += line + "\n";
  if (!err.empty() && err.back() != '\n' && !kept.empty()) kept.pop_back();
  return kept;
}

}  // namespace

void expect_input_error(const CliResult& r, const std::string& must_mention) {
  const std::string err = without_progress(r.err);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(err.find(must_mention), std::string::npos) << r.err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << "exactly one line: " << r.err;
  EXPECT_EQ(err.find('\n'), err.size() - 1) << "the line ends the output: " << r.err;
}

bool exists(const std::string& path) { return std::filesystem::exists(path); }

std::string fresh_dir(const std::string& tag) {
  static std::atomic<int> counter{0};
  const auto dir = std::filesystem::temp_directory_path() /
                   ("strand-test-" + tag + "-" + std::to_string(::getpid()) + "-" +
                    std::to_string(counter++));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

CliResult run_in_shell(const std::string& command, const std::string& dir) {
  const std::string out = dir + "/.stdout", err = dir + "/.stderr";
  const std::string cmd = "cd '" + dir + "' && (" + command + ") >'" + out + "' 2>'" + err + "'";
  const int status = std::system(cmd.c_str());
  CliResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return r;
}

CliResult run_strand(const std::string& args, const std::string& where) {
  const std::string dir = where.empty() ? fresh_dir("run") : where;
  return run_in_shell("'" + std::string(STRAND_CLI) + "' " + args, dir);
}

}  // namespace strand::testing
