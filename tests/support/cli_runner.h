// Runs the built `strand` binary for end-to-end tests: exit code, stdout and stderr.
#pragma once

#include <string>

namespace strand::testing {

struct CliResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

// `args` is appended to the binary path and run through the shell in `dir`.
// Without a directory it runs in a fresh one: tests run in parallel processes, and a shared
// working directory would mix their captured output.
CliResult run_strand(const std::string& args, const std::string& dir = "");
// Any shell command line (e.g. with variables before the program, or a pipe) run in `dir`.
CliResult run_in_shell(const std::string& command, const std::string& dir);
// A fresh empty directory under the system temp dir, unique per call.
std::string fresh_dir(const std::string& tag);
std::string slurp(const std::string& path);
// The house rule for bad input: exit code 2 and exactly one line on stderr that contains
// `must_mention` (the parameter and its limit). Callers check the absence of output files.
void expect_input_error(const CliResult& r, const std::string& must_mention);
bool exists(const std::string& path);

}  // namespace strand::testing
