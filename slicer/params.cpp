// Parameter table checking shared by the CLI and JSON jobs.
#include "slicer/params.h"

#include <charconv>
#include <cmath>

#include "slicer/input_error.h"
#include "slicer/unit_values.h"

namespace strand::slicer {

namespace {

std::string type_rule(ParamType t) {
  switch (t) {
    case ParamType::Number: return "must be a number";
    case ParamType::Integer: return "must be a whole number";
    case ParamType::Text: return "must be text";
    case ParamType::NumberList: return "must be a list of numbers like 0,90";
    case ParamType::Size2: return "must be a size like 36x36";
    case ParamType::Switch: return "must be on or off (true, false)";
  }
  return "";
}

bool in_range(const ParamDef& d, double v) {
  if (!std::isfinite(v)) return false;
  if (d.min && (d.min_exclusive ? v <= *d.min : v < *d.min)) return false;
  if (d.max && (d.max_exclusive ? v >= *d.max : v > *d.max)) return false;
  return true;
}

// A value normalised to its def's type, or the rule it breaks (and whether that rule is
// about units, whose message names the units instead of the table's unit).
struct Normalised {
  std::optional<nlohmann::json> value;
  std::string rule;
  bool unit_rule = false;
};

Normalised fail_type(const ParamDef& d) { return {std::nullopt, type_rule(d.type), false}; }

Normalised from_units(const ParamDef& d, const UnitValues& u) {
  if (!u.unit_problem.empty()) return {std::nullopt, u.unit_problem, true};
  if (u.malformed) return fail_type(d);
  return {nlohmann::json(u.values), "", false};
}

// A list element or size element: a number, or a string with one value and its unit.
Normalised element_of(const ParamDef& d, const nlohmann::json& e) {
  if (e.is_number()) return {e, "", false};
  if (!e.is_string()) return fail_type(d);
  const UnitValues u = parse_quantity(e.get<std::string>(), d.unit);
  Normalised n = from_units(d, u);
  if (n.value) n.value = u.values.front();
  return n;
}

Normalised numbers_of(const ParamDef& d, const nlohmann::json& v, std::size_t size) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& e : v) {
    Normalised n = element_of(d, e);
    if (!n.value) return n;
    out.push_back(*n.value);
  }
  if (out.empty() || (size && out.size() != size)) return fail_type(d);
  return {out, "", false};
}

Normalised paper_of(const ParamDef& d, const std::string& text) {
  const auto size = paper_size_mm(text);
  if (!size) {
    return {std::nullopt,
            "unknown paper (known: " + paper_names() +
                "; portrait, or add landscape: A4 landscape); or a size like 190x270" + d.unit,
            true};
  }
  return {nlohmann::json({(*size)[0], (*size)[1]}), "", false};
}

// A graded number (ParamDef::graded): "a..b" -> {"from": a, "to": b}, "a,b,c" or a JSON list
// -> [a, b, c]; a single value stays a number (so a plain value reads as before).
std::optional<Normalised> graded_of(const ParamDef& d, const nlohmann::json& v) {
  if (!d.graded) return std::nullopt;
  if (v.is_object()) {
    if (v.size() != 2 || !v.contains("from") || !v.contains("to")) return fail_type(d);
    const Normalised a = element_of(d, v.at("from")), b = element_of(d, v.at("to"));
    if (!a.value) return a;
    if (!b.value) return b;
    return Normalised{nlohmann::json{{"from", *a.value}, {"to", *b.value}}, "", false};
  }
  if (v.is_array()) {
    Normalised n = numbers_of(d, v, 0);
    if (n.value && n.value->size() == 1) n.value = n.value->front();
    return n;
  }
  if (!v.is_string()) return std::nullopt;
  std::string text = v.get<std::string>();
  const auto dots = text.find("..");
  if (dots != std::string::npos) {
    text.replace(dots, 2, ",");
    Normalised n = from_units(d, parse_quantities(text, d.unit, ','));
    if (n.value && n.value->size() != 2) return fail_type(d);
    if (n.value) n.value = nlohmann::json{{"from", (*n.value)[0]}, {"to", (*n.value)[1]}};
    return n;
  }
  if (text.find(',') == std::string::npos) return std::nullopt;
  return from_units(d, parse_quantities(text, d.unit, ','));
}

// "on", "true", "yes", "1" and their opposites, in any case.
Normalised switch_of(const ParamDef& d, const nlohmann::json& v) {
  if (v.is_boolean()) return {v, "", false};
  if (!v.is_string()) return fail_type(d);
  if (match_choice(v.get<std::string>(), {"on", "true", "yes", "1"})) return {true, "", false};
  if (match_choice(v.get<std::string>(), {"off", "false", "no", "0"})) return {false, "", false};
  return fail_type(d);
}

// Normalises a given JSON value to the def's type: numbers as they are, text read with its
// units into the table's unit.
Normalised normalise(const ParamDef& d, const nlohmann::json& v) {
  if (auto g = graded_of(d, v)) return *g;
  switch (d.type) {
    case ParamType::Switch: return switch_of(d, v);
    case ParamType::Number:
      if (v.is_number()) return {v, "", false};
      if (v.is_string()) {
        Normalised n = from_units(d, parse_quantity(v.get<std::string>(), d.unit));
        if (n.value) n.value = n.value->front();
        return n;
      }
      return fail_type(d);
    case ParamType::Integer: {
      Normalised n = fail_type(d);
      if (v.is_number()) {
        n = {v, "", false};
      } else if (v.is_string()) {
        n = from_units(d, parse_quantity(v.get<std::string>(), d.unit));
        if (n.value) n.value = n.value->front();
      }
      if (!n.value || n.value->is_number_integer()) return n;
      const double x = n.value->get<double>();
      if (std::floor(x) == x && std::abs(x) < 1e15) {
        return {nlohmann::json(static_cast<long long>(x)), "", false};
      }
      return fail_type(d);
    }
    case ParamType::Text:
      if (v.is_string()) return {v, "", false};
      return fail_type(d);
    case ParamType::NumberList:
      if (v.is_number()) return {nlohmann::json::array({v}), "", false};
      if (v.is_string()) return from_units(d, parse_quantities(v.get<std::string>(), d.unit, ','));
      if (v.is_array()) return numbers_of(d, v, 0);
      return fail_type(d);
    case ParamType::Size2:
      if (v.is_string()) {
        const std::string text = v.get<std::string>();
        if (d.paper && looks_like_name(text)) return paper_of(d, text);
        Normalised n = from_units(d, parse_quantities(text, d.unit, 'x'));
        if (n.value && n.value->size() != 2) return fail_type(d);
        return n;
      }
      if (v.is_array()) return numbers_of(d, v, 2);
      return fail_type(d);
  }
  return fail_type(d);
}

}  // namespace

std::string value_text(const nlohmann::json& v) {
  if (v.is_number()) return short_number(v.get<double>());
  if (v.is_object() && v.size() == 2 && v.contains("from") && v.contains("to")) {
    return value_text(v.at("from")) + ".." + value_text(v.at("to"));
  }
  if (v.is_string()) return v.get<std::string>();
  if (v.is_array()) {
    std::string s;
    for (const auto& e : v) s += (s.empty() ? "" : ",") + value_text(e);
    return s;
  }
  return v.dump();
}

std::string short_number(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[64];
  auto res = std::to_chars(buf, buf + sizeof buf, v);  // shortest round-trip form
  return std::string(buf, res.ptr);
}

std::string describe_rule(const ParamDef& d) {
  if (!d.choices.empty()) {
    std::string s = "must be one of ";
    for (std::size_t i = 0; i < d.choices.size(); ++i) s += (i ? ", " : "") + d.choices[i];
    return s;
  }
  const char* each = (d.type == ParamType::NumberList || d.type == ParamType::Size2) ? "each " : "";
  if (d.min && d.max) {
    return std::string("must ") + (*each ? "each " : "") + "be in " +
           (d.min_exclusive ? "(" : "[") + short_number(*d.min) + ", " + short_number(*d.max) +
           (d.max_exclusive ? ")" : "]");
  }
  if (d.min) {
    return std::string("must ") + (*each ? "each " : "") + "be " +
           (d.min_exclusive ? "> " : ">= ") + short_number(*d.min);
  }
  if (d.max) {
    return std::string("must ") + (*each ? "each " : "") + "be " +
           (d.max_exclusive ? "< " : "<= ") + short_number(*d.max);
  }
  return type_rule(d.type);
}

std::string problem(const std::string& table, const std::string& key, const nlohmann::json& value,
                    const std::string& rule, const std::string& unit) {
  std::string s = table + "." + key + " = " + value_text(value) + ": " + rule;
  if (!unit.empty()) s += " (" + unit + ")";
  return s;
}

nlohmann::json parse_param_text(const ParamTable& table, const ParamDef& def,
                                const std::string& text) {
  const Normalised n = normalise(def, text);
  if (!n.value) throw InputError(problem(table.name, def.key, text, n.rule, n.unit_rule ? "" : def.unit));
  return *n.value;
}

nlohmann::json resolve_params(const ParamTable& table, const nlohmann::json& given) {
  std::vector<std::string> problems;
  nlohmann::json out = nlohmann::json::object();
  if (!given.is_object()) throw InputError(table.name + ": parameters must be a JSON object");
  for (const auto& [key, value] : given.items()) {
    bool known = false;
    for (const auto& d : table.defs) known = known || d.key == key;
    if (!known) {
      std::string keys;
      for (const auto& d : table.defs) keys += (keys.empty() ? "" : ", ") + d.key;
      problems.push_back(table.name + "." + key + ": unknown parameter (known: " + keys + ")");
    }
  }
  for (const auto& d : table.defs) {
    const bool has = given.contains(d.key) && !given.at(d.key).is_null();
    if (!has) {
      if (!d.default_value.is_null()) out[d.key] = normalise(d, d.default_value).value.value_or(d.default_value);
      continue;
    }
    const auto& raw = given.at(d.key);
    const Normalised n = normalise(d, raw);
    if (!n.value) {
      problems.push_back(problem(table.name, d.key, raw, n.rule, n.unit_rule ? "" : d.unit));
      continue;
    }
    auto v = n.value;
    bool ok = true;
    if (v->is_structured() && d.graded) {
      for (const auto& e : *v) ok = ok && in_range(d, e.get<double>());
    } else if (d.type == ParamType::Number || d.type == ParamType::Integer) {
      ok = in_range(d, v->get<double>());
    } else if (d.type == ParamType::NumberList || d.type == ParamType::Size2) {
      for (const auto& e : *v) ok = ok && in_range(d, e.get<double>());
    } else if (!d.choices.empty()) {
      const auto choice = match_choice(v->get<std::string>(), d.choices);
      ok = choice.has_value();
      if (ok) v = nlohmann::json(*choice);  // the table's spelling: "FDM" -> "fdm"
    }
    if (!ok) {
      problems.push_back(problem(table.name, d.key, raw, describe_rule(d), d.unit));
      continue;
    }
    out[d.key] = *v;
  }
  if (!problems.empty()) throw InputError(problems);
  return out;
}

}  // namespace strand::slicer
