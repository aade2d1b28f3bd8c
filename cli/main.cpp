// strand: toolpaths for Direct Ink Writing and pen plotting. Exit codes: 0 ok,
// 1 a check found problems (or a sweep point failed), 2 bad input (one line on stderr,
// no output file).
#include <CLI/CLI.hpp>
#include <iostream>
#include <new>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/manual.h"
#include "cli/progress_bar.h"
#include "cli/suggest.h"
#include "cli/version.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"

namespace {

// Errors are one line whatever the input put into them: control characters (a newline in a
// machine name or a job key) are shown escaped, and the line is cut at 1000 characters.
std::string one_line(const std::string& text) {
  std::string out;
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (u < 0x20 || u == 0x7f) {
      static const char* const kHex = "0123456789abcdef";
      out += std::string("\\x") + kHex[u >> 4] + kHex[u & 15];
    } else {
      out += c;
    }
    if (out.size() > 1000) return out.substr(0, 997) + "...";
  }
  return out;
}

int fail(const std::string& message) {
  std::cerr << "strand: error: " << one_line(message) << "\n";
  return 2;
}

// --quiet and --progress on strand itself and on every command (so each --help, manual page
// and completion lists them): the same two switches wherever they are written.
void add_global_flags(CLI::App& app, bool& quiet, bool& progress) {
  app.add_flag("--quiet", quiet, "no progress on stderr (bars, phase lines)");
  app.add_flag("--progress", progress,
               "a progress line per phase on stderr from the start, even for short runs and "
               "without a terminal (default: a bar on a terminal, else lines once a run passes 1 s)");
  for (CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
    add_global_flags(*sub, quiet, progress);
  }
}

int run(int argc, char** argv) {
  CLI::App app{"strand: toolpaths for Direct Ink Writing and pen plotting (mm, mm/min)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", strand::cli::version_text());
  strand::cli::Action action;
  strand::cli::add_generator_commands(app, action);
  strand::cli::add_job_command(app, action);
  strand::cli::add_machines_command(app, action);
  strand::cli::add_plot_command(app, action);
  strand::cli::add_text_command(app, action);
  strand::cli::add_trace_command(app, action);
  strand::cli::add_send_command(app, action);
  strand::cli::add_check_command(app, action);
  strand::cli::add_flow_command(app, action);
  strand::cli::add_sweep_command(app, action);
  strand::cli::add_preview_command(app, action);
  strand::cli::add_slice_command(app, action);
  strand::cli::add_mesh_command(app, action);
  strand::cli::add_serve_command(app, action);
  strand::cli::add_measure_command(app, action);
  strand::cli::add_calibrate_command(app, action);
  strand::cli::add_manual_commands(app, action);
  bool quiet = false, progress = false;
  add_global_flags(app, quiet, progress);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion&) {
    std::cout << strand::cli::version_text();
    return 0;
  } catch (const CLI::ParseError& e) {
    // An unknown command or flag is named with the nearest known one; other refusals keep
    // CLI11's message.
    const std::vector<std::string> args(argv + 1, argv + argc);
    return fail(strand::cli::explain_unknown_words(app, args).value_or(e.what()));
  }
  strand::cli::set_progress_mode(quiet      ? strand::cli::ProgressMode::Quiet
                                  : progress ? strand::cli::ProgressMode::Always
                                             : strand::cli::ProgressMode::Auto);
  return action ? action() : 0;
}

}  // namespace

int main(int argc, char** argv) {
  strand::slicer::install_signal_cleanup();
  // No exception leaves main: input errors and library exceptions alike end in one line and
  // exit code 2, after the output transactions have removed their temp files.
  try {
    return run(argc, argv);
  } catch (const strand::InputError& e) {
    return fail(e.what());
  } catch (const nlohmann::json::exception& e) {
    return fail(std::string("unexpected value in a JSON input (") + e.what() + ")");
  } catch (const std::bad_alloc&) {
    return fail("out of memory: the input asks for more than this machine has");
  } catch (const std::exception& e) {
    return fail(std::string("internal error: ") + e.what());
  }
}
