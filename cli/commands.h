// Sub-command registration for the `strand` CLI. Each adder wires flags to a handler that
// throws InputError for bad input; main() turns that into one line and exit code 2.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>

namespace strand::cli {

// Set by the chosen sub-command; returns the process exit code.
using Action = std::function<int()>;

void add_generator_commands(CLI::App& app, Action& action);
void add_job_command(CLI::App& app, Action& action);
void add_machines_command(CLI::App& app, Action& action);
void add_plot_command(CLI::App& app, Action& action);
void add_text_command(CLI::App& app, Action& action);
void add_trace_command(CLI::App& app, Action& action);
void add_send_command(CLI::App& app, Action& action);
void add_check_command(CLI::App& app, Action& action);
void add_flow_command(CLI::App& app, Action& action);
void add_sweep_command(CLI::App& app, Action& action);
void add_preview_command(CLI::App& app, Action& action);
void add_slice_command(CLI::App& app, Action& action);
void add_mesh_command(CLI::App& app, Action& action);  // in slice_command.cpp
void add_serve_command(CLI::App& app, Action& action);
void add_measure_command(CLI::App& app, Action& action);    // ink tests (issue 32)
void add_calibrate_command(CLI::App& app, Action& action);

}  // namespace strand::cli
