// Command-line flags built from a parameter table (slicer/params.h): one `--key` per
// parameter with its unit and default in --help, and the given values read back as JSON.
#pragma once

#include <CLI/CLI.hpp>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
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
// A flag outside the tables that measures something (--arc-tolerance, flow's --speed): a
// number with an optional unit ("0.02", "20um", "5 mm/s") converted to `unit` as table values
// are; malformed text or a unit of another dimension is refused naming the flag, e.g.
// "--arc-tolerance = 3mm/s: expected a length (mm, cm, m, um, in)".
CLI::Option* add_quantity_option(CLI::App* sub, const std::string& names, double& target, const std::string& unit,
                                 const std::string& help);
CLI::Option* add_quantity_option(CLI::App* sub, const std::string& names, std::optional<double>& target,
                                 const std::string& unit, const std::string& help);
// The flags the user gave, converted to their JSON form (InputError on malformed text).
nlohmann::json given_params(const slicer::ParamTable& table, const ParamFlags& flags);

}  // namespace strand::cli
