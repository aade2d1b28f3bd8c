// strand: toolpaths for Direct Ink Writing and pen plotting. Exit codes: 0 ok,
// 1 a check found problems (or a sweep point failed), 2 bad input (one line on stderr,
// no output file).
#include <CLI/CLI.hpp>
#include <iostream>

#include "cli/commands.h"
#include "slicer/input_error.h"

int main(int argc, char** argv) {
  CLI::App app{"strand: toolpaths for Direct Ink Writing and pen plotting (mm, mm/min)"};
  app.require_subcommand(1);
  strand::cli::Action action;
  strand::cli::add_generator_commands(app, action);
  strand::cli::add_job_command(app, action);
  strand::cli::add_machines_command(app, action);
  strand::cli::add_plot_command(app, action);
  strand::cli::add_check_command(app, action);
  strand::cli::add_flow_command(app, action);
  strand::cli::add_sweep_command(app, action);
  strand::cli::add_preview_command(app, action);
  strand::cli::add_slice_command(app, action);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "strand: error: " << e.what() << "\n";
    return 2;
  }
  try {
    return action ? action() : 0;
  } catch (const strand::InputError& e) {
    std::cerr << "strand: error: " << e.what() << "\n";
    return 2;
  }
}
