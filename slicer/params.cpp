// Parameter table checking shared by the CLI and JSON jobs.
#include "slicer/params.h"

#include <charconv>
#include <cmath>
#include <sstream>

#include "slicer/input_error.h"

namespace strand::slicer {

namespace {

std::string type_rule(ParamType t) {
  switch (t) {
    case ParamType::Number: return "must be a number";
    case ParamType::Integer: return "must be a whole number";
    case ParamType::Text: return "must be text";
    case ParamType::NumberList: return "must be a list of numbers like 0,90";
    case ParamType::Size2: return "must be a size like 36x36";
  }
  return "";
}

bool in_range(const ParamDef& d, double v) {
  if (!std::isfinite(v)) return false;
  if (d.min && (d.min_exclusive ? v <= *d.min : v < *d.min)) return false;
  if (d.max && (d.max_exclusive ? v >= *d.max : v > *d.max)) return false;
  return true;
}

std::optional<double> parse_double(const std::string& s) {
  std::istringstream in(s);
  in.imbue(std::locale::classic());
  double v = 0;
  in >> v;
  if (in.fail() || !in.eof()) {
    // allow trailing spaces
    std::string rest;
    if (!in.fail() && (in >> rest, rest.empty())) return v;
    return std::nullopt;
  }
  return v;
}

std::optional<std::vector<double>> parse_list(const std::string& s, char sep) {
  std::vector<double> out;
  std::string item;
  std::istringstream in(s);
  while (std::getline(in, item, sep)) {
    auto v = parse_double(item);
    if (!v) return std::nullopt;
    out.push_back(*v);
  }
  if (out.empty()) return std::nullopt;
  return out;
}

// Normalises a given JSON value to the def's type; nullopt if it is not of that type.
std::optional<nlohmann::json> normalise(const ParamDef& d, const nlohmann::json& v) {
  switch (d.type) {
    case ParamType::Number:
      if (v.is_number()) return v;
      return std::nullopt;
    case ParamType::Integer:
      if (v.is_number_integer()) return v;
      if (v.is_number_float() && std::floor(v.get<double>()) == v.get<double>() &&
          std::abs(v.get<double>()) < 1e15) {
        return nlohmann::json(static_cast<long long>(v.get<double>()));
      }
      return std::nullopt;
    case ParamType::Text:
      if (v.is_string()) return v;
      return std::nullopt;
    case ParamType::NumberList:
      if (v.is_number()) return nlohmann::json::array({v});
      if (v.is_string()) {
        auto l = parse_list(v.get<std::string>(), ',');
        if (!l) return std::nullopt;
        return nlohmann::json(*l);
      }
      if (v.is_array() && !v.empty()) {
        for (const auto& e : v) {
          if (!e.is_number()) return std::nullopt;
        }
        return v;
      }
      return std::nullopt;
    case ParamType::Size2:
      if (v.is_string()) {
        auto l = parse_list(v.get<std::string>(), 'x');
        if (!l || l->size() != 2) return std::nullopt;
        return nlohmann::json(*l);
      }
      if (v.is_array() && v.size() == 2 && v[0].is_number() && v[1].is_number()) return v;
      return std::nullopt;
  }
  return std::nullopt;
}

}  // namespace

std::string value_text(const nlohmann::json& v) {
  if (v.is_number()) return short_number(v.get<double>());
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
  nlohmann::json v = text;
  if (def.type == ParamType::Number || def.type == ParamType::Integer) {
    auto d = parse_double(text);
    if (!d) throw InputError(problem(table.name, def.key, text, type_rule(def.type), def.unit));
    v = *d;
  }
  auto n = normalise(def, v);
  if (!n) throw InputError(problem(table.name, def.key, text, type_rule(def.type), def.unit));
  return *n;
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
      if (!d.default_value.is_null()) out[d.key] = normalise(d, d.default_value).value_or(d.default_value);
      continue;
    }
    const auto& raw = given.at(d.key);
    auto v = normalise(d, raw);
    if (!v) {
      problems.push_back(problem(table.name, d.key, raw, type_rule(d.type), d.unit));
      continue;
    }
    bool ok = true;
    if (d.type == ParamType::Number || d.type == ParamType::Integer) {
      ok = in_range(d, v->get<double>());
    } else if (d.type == ParamType::NumberList || d.type == ParamType::Size2) {
      for (const auto& e : *v) ok = ok && in_range(d, e.get<double>());
    } else if (!d.choices.empty()) {
      ok = false;
      for (const auto& c : d.choices) ok = ok || c == v->get<std::string>();
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
