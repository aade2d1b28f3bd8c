// Manual pages and shell completion, generated from the same CLI11 tables as --help, so a
// flag added to a command appears in all three.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "cli/commands.h"

namespace strand::cli {

// roff for man(1): `command` null gives strand(1) (commands, exit status), otherwise
// strand-<command>(1) with every flag, its value type, default and description.
std::string man_page(const CLI::App& app, const CLI::App* command, const std::string& version);

// A bash completion function for `strand`: commands, each command's flags, machine names
// after --machine, file names elsewhere.
std::string bash_completion(const CLI::App& app, const std::vector<std::string>& machines);

// zsh: the same function through zsh's bash completion layer.
std::string zsh_completion(const CLI::App& app, const std::vector<std::string>& machines);

// `strand manual [COMMAND] [--dir DIR]` and `strand completion bash|zsh`.
void add_manual_commands(CLI::App& app, Action& action);

}  // namespace strand::cli
