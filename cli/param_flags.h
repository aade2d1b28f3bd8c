// Command-line flags built from a parameter table (slicer/params.h): one `--key` per
// parameter with its unit and default in --help, and the given values read back as JSON.
#pragma once

#include <CLI/CLI.hpp>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "slicer/params.h"

namespace strand::cli {

// The text each flag received and the option behind it (to tell "given" from "default").
struct ParamFlags {
  std::map<std::string, std::string> text;
  std::map<std::string, CLI::Option*> options;
};

// "help [unit] (default value)" for --help.
std::string help_for(const slicer::ParamDef& d);
// The placeholder shown in --help: the unit for numbers, the shape for lists and sizes.
std::string type_name_for(const slicer::ParamDef& d);
// Adds one option per table entry to `sub`; `flags` must outlive the parse.
void add_param_flags(CLI::App* sub, const slicer::ParamTable& table, ParamFlags& flags);
// The flags the user gave, converted to their JSON form (InputError on malformed text).
nlohmann::json given_params(const slicer::ParamTable& table, const ParamFlags& flags);

}  // namespace strand::cli
