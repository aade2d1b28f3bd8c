// Shell-based headless Chromium runner (tests only).
#include "tests/support/chromium.h"

#include <sys/wait.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>

#include "tests/support/cli_runner.h"

namespace strand::testing {

std::string chromium_path() {
  for (const char* p : {"/usr/bin/chromium", "/usr/bin/chromium-browser"}) {
    if (std::filesystem::exists(p)) return p;
  }
  return "";
}

ChromiumRun run_chromium(const std::string& dir, const std::string& mode, const std::string& page) {
  static std::atomic<int> counter{0};
  const std::string profile = dir + "/chromium-profile-" + std::to_string(counter++);
  const std::string cmd = "timeout 90 '" + chromium_path() +
                          "' --headless --no-sandbox --disable-gpu --disable-quic --no-first-run"
                          " --disable-background-networking --disable-component-update --disable-sync"
                          " --enable-logging=stderr --v=0 --window-size=900,700 --user-data-dir='" + profile +
                          "' " + mode + " '" + (page.rfind("http://", 0) == 0 ? "" : "file://") + page + "' >'" + dir + "/chromium.out' 2>'" + dir + "/chromium.err'";
  const int status = std::system(cmd.c_str());
  ChromiumRun r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(dir + "/chromium.out");
  r.log = slurp(dir + "/chromium.err");
  std::filesystem::remove_all(profile);
  return r;
}

// Chromium writes console messages as "INFO:CONSOLE:1] \"message\"" (older builds:
// "CONSOLE(1)"); uncaught exceptions also start with "Uncaught".
bool has_console_output(const std::string& log) {
  for (const char* bad : {"Uncaught", ":CONSOLE", "CONSOLE(", "SyntaxError", "TypeError", "ReferenceError"}) {
    if (log.find(bad) != std::string::npos) return true;
  }
  return false;
}

}  // namespace strand::testing
