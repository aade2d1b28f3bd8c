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

// True when the log holds a console message or an uncaught error (pages under test log nothing).
bool has_console_output(const std::string& log);

}  // namespace strand::testing
