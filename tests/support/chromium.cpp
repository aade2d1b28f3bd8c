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

ChromiumRun run_browser_script(const std::string& script, const std::string& url, const std::string& dir) {
  ChromiumRun r;
  if (!std::filesystem::exists("/usr/bin/chromedriver") || std::system("/usr/bin/python3 -c 'import selenium' 2>/dev/null") != 0) {
    r.exit_code = 77;
    return r;
  }
  const std::string path = std::string(STRAND_SOURCE_DIR) + "/" + script;
  const std::string cmd = "cd '" + dir + "' && PYTHONPATH='" + std::string(STRAND_SOURCE_DIR) +
                          "/tests/support/browser' timeout 180 /usr/bin/python3 '" + path + "' '" + url + "' '" + dir +
                          "' >'" + dir + "/browser.out' 2>'" + dir + "/browser.err'";
  const int status = std::system(cmd.c_str());
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(dir + "/browser.out");
  r.log = slurp(dir + "/browser.err");
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
