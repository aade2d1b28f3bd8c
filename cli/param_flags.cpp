// Flags from parameter tables: help text, placeholders, and reading the given values.
#include "cli/param_flags.h"

#include <functional>
#include <utility>

#include "slicer/unit_values.h"

namespace strand::cli {

std::string help_for(const slicer::ParamDef& d) {
  std::string h = d.help;
  if (!d.unit.empty()) h += " [" + d.unit + "]";
  if (!d.default_value.is_null()) {
    const auto& v = d.default_value;
    h += " (default " +
         (v.is_string() ? v.get<std::string>() : v.is_number() ? slicer::short_number(v.get<double>()) : slicer::value_text(v)) +
         ")";
  } else if (!d.default_text.empty()) {
    h += " (default " + d.default_text + ")";
  }
  if (!d.choices.empty()) {
    std::string list;
    for (const auto& c : d.choices) list += (list.empty() ? "" : "|") + c;
    h += " {" + list + "}";
  }
  return h;
}

std::string type_name_for(const slicer::ParamDef& d) {
  switch (d.type) {
    case slicer::ParamType::Integer: return "N";
    case slicer::ParamType::NumberList: return "LIST";
    case slicer::ParamType::Size2: return d.paper ? "WxH|PAPER" : "WxD";
    case slicer::ParamType::Text: return "NAME";
    case slicer::ParamType::Switch: return "";
    case slicer::ParamType::Number: break;
  }
  if (d.unit == "mm") return "MM";
  if (d.unit == "mm/min") return "MM_PER_MIN";
  if (d.unit == "deg") return "DEG";
  return "X";
}

void add_param_flags(CLI::App* sub, const slicer::ParamTable& table, ParamFlags& flags) {
  for (const auto& d : table.defs) {
    if (d.type == slicer::ParamType::Switch) {  // bare --stagger is on; --stagger=off too
      flags.options[d.key] = sub->add_flag("--" + d.key, flags.text[d.key], help_for(d));
      continue;
    }
    flags.options[d.key] = sub->add_option("--" + d.key, flags.text[d.key], help_for(d))->type_name(type_name_for(d));
  }
}

namespace {

CLI::Option* add_quantity(CLI::App* sub, const std::string& names, std::function<void(double)> set,
                          const std::string& unit, const std::string& help) {
  const std::string flag = names.substr(names.rfind(',') == std::string::npos ? 0 : names.rfind(',') + 1);
  const auto read = [set = std::move(set), flag, unit](const std::string& text) {
    const slicer::UnitValues v = slicer::parse_quantity(text, unit);
    if (v.malformed) throw CLI::ValidationError(flag + " = " + text + ": must be a number, " + slicer::expected_units(unit));
    if (!v.unit_problem.empty()) throw CLI::ValidationError(flag + " = " + text + ": " + v.unit_problem);
    set(v.values.front());
  };
  return sub->add_option_function<std::string>(names, read, help)
      ->type_name(unit == "mm" ? "MM" : unit == "mm/min" ? "MM_PER_MIN" : unit == "deg" ? "DEG" : "X");
}

}  // namespace

CLI::Option* add_quantity_option(CLI::App* sub, const std::string& names, double& target, const std::string& unit,
                                 const std::string& help) {
  return add_quantity(sub, names, [&target](double v) { target = v; }, unit, help);
}

CLI::Option* add_quantity_option(CLI::App* sub, const std::string& names, std::optional<double>& target,
                                 const std::string& unit, const std::string& help) {
  return add_quantity(sub, names, [&target](double v) { target = v; }, unit, help);
}

nlohmann::json given_params(const slicer::ParamTable& table, const ParamFlags& flags) {
  nlohmann::json given = nlohmann::json::object();
  for (const auto& d : table.defs) {
    if (flags.options.at(d.key)->count() > 0) {
      given[d.key] = slicer::parse_param_text(table, d, flags.text.at(d.key));
    }
  }
  return given;
}

}  // namespace strand::cli
