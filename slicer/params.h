// Parameter tables: every user-facing parameter declared once (key, unit, range, default,
// help). The CLI builds its flags from a table and the JSON job loader checks against it,
// so both give the same messages.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace strand::slicer {

enum class ParamType {
  Number,      // real, JSON number
  Integer,     // whole number
  Text,        // free text or a name
  NumberList,  // "0,90" on the CLI, [0, 90] in JSON
  Size2,       // "36x36" on the CLI, [36, 36] or "36x36" in JSON
  Switch,      // on or off: a bare `--stagger` on the CLI, true or false in JSON
};

struct ParamDef {
  std::string key;   // CLI long flag without dashes, JSON key: "layer-height"
  ParamType type = ParamType::Number;
  std::string unit;  // "mm", "mm/min", "deg", "" for counts and factors
  std::string help;
  std::optional<double> min;  // applies to numbers, integers and every list/size element
  bool min_exclusive = false;
  std::optional<double> max;
  bool max_exclusive = false;
  nlohmann::json default_value = nullptr;  // null: no fixed default
  std::string default_text;                // shown in help when the default is computed
  std::vector<std::string> choices;        // Text only: allowed values (any case), empty = any
  bool paper = false;                      // Size2 only: also a paper name ("A4 landscape")
  // Number only: also a graded value, "0.8..1.6" (JSON {"from": 0.8, "to": 1.6}) or a list
  // "0.8,1.2,1.6" (JSON [0.8, 1.2, 1.6]); one value stays a plain number.
  bool graded = false;
};

struct ParamTable {
  std::string name;  // prefix for messages: "scaffold"
  std::vector<ParamDef> defs;
};

// Checks given values (a JSON object) against the table: unknown keys, types, units, ranges
// and choices. Returns the values with fixed defaults filled in, Size2 and lists normalised
// to arrays of numbers in the table's unit (a JSON string may carry units: "0.84mm",
// "36x36mm", "A4" where `paper` is set; see slicer/unit_values.h), choices in the table's
// spelling. Throws InputError naming every problem as "table.key = value: rule (unit)".
nlohmann::json resolve_params(const ParamTable& table, const nlohmann::json& given);

// Converts command-line text to the JSON form of `def` ("36x36" -> [36, 36], "840um" ->
// 0.84 for a length in mm); throws InputError on text that is not of the type, or carries a
// unit of another dimension ("scaffold.nozzle = 3mm/s: expected a length (mm, cm, m, um, in)").
nlohmann::json parse_param_text(const ParamTable& table, const ParamDef& def,
                                const std::string& text);

// "must be > 0", "must be in [0.5, 1]" — the rule part of a message.
std::string describe_rule(const ParamDef& def);
// One problem line in the house format.
std::string problem(const std::string& table, const std::string& key,
                    const nlohmann::json& value, const std::string& rule,
                    const std::string& unit);
// Short text for a number: 0.84, 250, 1e-05 (used in messages and file names).
std::string short_number(double v);
// A parameter value as a user writes it: numbers short, text as is, lists joined by commas
// (0,90); used in error messages and G-code headers.
std::string value_text(const nlohmann::json& v);

}  // namespace strand::slicer
