// Flags from parameter tables: help text, placeholders, and reading the given values.
#include "cli/param_flags.h"

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
    case slicer::ParamType::Number: break;
  }
  if (d.unit == "mm") return "MM";
  if (d.unit == "mm/min") return "MM_PER_MIN";
  if (d.unit == "deg") return "DEG";
  return "X";
}

void add_param_flags(CLI::App* sub, const slicer::ParamTable& table, ParamFlags& flags) {
  for (const auto& d : table.defs) {
    flags.options[d.key] = sub->add_option("--" + d.key, flags.text[d.key], help_for(d))->type_name(type_name_for(d));
  }
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
