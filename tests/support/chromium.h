// Headless Chromium for tests of HTML output: DOM after scripts ran, screenshots, console.
#pragma once

#include <string>

namespace strand::testing {

// Path of the Debian chromium binary, or "" when it is not installed.
std::string chromium_path();

struct ChromiumRun {
  int exit_code = -1;
  std::string out;  // --dump-dom: the DOM after the page's scripts ran
  std::string log;  // stderr with --enable-logging: console messages appear as ":CONSOLE"
};

// Runs `chromium --headless ... <mode> file://<page>` with a fresh profile under `dir`;
// `mode` is e.g. "--dump-dom" or "--screenshot=/path/shot.png". A `page` starting with
// "http://" is opened as that URL (a test server on 127.0.0.1).
ChromiumRun run_chromium(const std::string& dir, const std::string& mode, const std::string& page);

// Runs `python3 <script> <url> <dir>` (script relative to the source tree, e.g.
// "tests/serve/browser/draw.py"; it can import strand_browser) (Debian's python3-selenium and
// chromium-driver; see strand_browser.py). The script exits 0 when its expectations held, else
// prints one line on stderr. exit_code is 77 when selenium or chromedriver is not installed.
ChromiumRun run_browser_script(const std::string& script, const std::string& url, const std::string& dir);

// True when the log holds a console message or an uncaught error (pages under test log nothing).
bool has_console_output(const std::string& log);

}  // namespace strand::testing
