// Sweep file checking and expansion into points.
#include "jobs/sweep_spec.h"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <set>

#include "slicer/input_error.h"
#include "slicer/json_input.h"
#include "slicer/params.h"

namespace strand::jobs {

namespace {

// More points than this is surely a typo in a range.
constexpr std::size_t kMaxPoints = 100000;

const slicer::ParamDef* find_def(const slicer::ParamTable& t, const std::string& key) {
  for (const auto& d : t.defs) {
    if (d.key == key) return &d;
  }
  return nullptr;
}

std::string table_keys(const slicer::ParamTable& t) {
  std::string s;
  for (const auto& d : t.defs) s += (s.empty() ? "" : ", ") + d.key;
  return s;
}

double round_sig(double v) {
  if (v == 0.0) return 0.0;
  const double scale = std::pow(10.0, 11 - static_cast<int>(std::floor(std::log10(std::abs(v)))));
  return std::round(v * scale) / scale;
}

std::vector<nlohmann::json> vary_values(const nlohmann::json& v, const std::string& where) {
  if (v.is_object()) return range_values(v, where);
  if (!v.is_array()) throw InputError(where + ": must be a list of values or {\"from\", \"to\", \"step\"}");
  if (v.empty()) throw InputError(where + ": empty list (the product would be empty)");
  return std::vector<nlohmann::json>(v.begin(), v.end());
}

// Text of a value for file names: 0.84, 36x36, names with unsafe characters replaced.
std::string name_text(const nlohmann::json& v) {
  if (v.is_number()) return slicer::short_number(v.get<double>());
  if (v.is_array()) {
    std::string s;
    for (const auto& e : v) s += (s.empty() ? "" : "x") + name_text(e);
    return s;
  }
  std::string s = v.is_string() ? v.get<std::string>() : v.dump();
  for (char& c : s) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '-') c = '_';
  }
  return s;
}

void check_keys(const nlohmann::json& j) {
  for (const auto& [k, v] : j.items()) {
    if (k != "job" && k != "vary" && k != "mode" && k != "where" && k != "description") {
      throw InputError("sweep." + k + ": unknown key (job, vary, mode, where, description)");
    }
  }
  if (!j.contains("job")) throw InputError("sweep.job: missing (the base job)");
  if (!j.contains("vary") || !j.at("vary").is_object() || j.at("vary").empty()) {
    throw InputError("sweep.vary: missing or empty (give {parameter: [values]})");
  }
}

std::map<std::string, double> constraint_values(const SweepSpec& s, const nlohmann::json& params) {
  std::map<std::string, double> values;
  for (const auto& d : s.job.generator->table().defs) {
    const nlohmann::json& v = params.contains(d.key) ? params.at(d.key) : d.default_value;
    if (v.is_number()) values[d.key] = v.get<double>();
  }
  return values;
}

// Drops or fails the point by the first constraint it breaks.
void apply_where(const SweepSpec& s, SweepPoint& p) {
  const auto values = constraint_values(s, p.params);
  for (std::size_t c = 0; c < s.where.size(); ++c) {
    for (const auto& name : s.where[c].names) {
      if (!values.count(name)) {
        p.error = "sweep.where[" + std::to_string(c) + "]: " + name + " has no value at this point";
        return;
      }
    }
    if (!holds(s.where[c], values)) {
      p.dropped = "where[" + std::to_string(c) + "] \"" + s.where[c].text + "\" is false";
      return;
    }
  }
}

// "where": a list of constraint strings over number parameters of the generator.
std::vector<Constraint> parse_where(const nlohmann::json& where, const SweepSpec& s) {
  const auto& table = s.job.generator->table();
  if (!where.is_array()) throw InputError("sweep.where: must be a list of strings such as \"gap >= nozzle\"");
  std::vector<Constraint> out;
  for (std::size_t c = 0; c < where.size(); ++c) {
    const std::string path = "sweep.where[" + std::to_string(c) + "]";
    if (!where[c].is_string()) throw InputError(path + ": must be a string such as \"gap >= nozzle\"");
    out.push_back(parse_constraint(where[c].get<std::string>(), path));
    for (const auto& name : out.back().names) {
      const auto* d = find_def(table, name);
      if (!d || (d->type != slicer::ParamType::Number && d->type != slicer::ParamType::Integer)) {
        throw InputError(path + " = \"" + where[c].get<std::string>() + "\": " + name +
                         " is not a number parameter of " + s.job.generator->name);
      }
    }
  }
  return out;
}

}  // namespace

std::vector<nlohmann::json> range_values(const nlohmann::json& r, const std::string& where) {
  for (const char* k : {"from", "to", "step"}) {
    if (!r.contains(k) || !r.at(k).is_number()) throw InputError(where + "." + k + ": missing or not a number");
  }
  if (r.size() != 3) throw InputError(where + ": a range has exactly the keys from, to, step");
  const double from = r["from"].get<double>(), to = r["to"].get<double>(), step = r["step"].get<double>();
  if (step == 0.0 || !std::isfinite(step)) throw InputError(where + ".step = 0: must not be 0");
  if ((to - from) * step < 0.0) {
    throw InputError(where + ".step = " + slicer::short_number(step) + ": must have the sign of to - from = " +
                     slicer::short_number(to - from));
  }
  // Slack so that 0.8 + 2 * 0.4 reaches 1.6 despite binary rounding.
  const double count = std::floor((to - from) / step + 1e-9) + 1.0;
  if (count > static_cast<double>(kMaxPoints)) throw InputError(where + ": more than 100000 values");
  const bool integers = r["from"].is_number_integer() && r["to"].is_number_integer() && r["step"].is_number_integer();
  std::vector<nlohmann::json> out;
  for (long i = 0; i < static_cast<long>(count); ++i) {
    const double v = from + static_cast<double>(i) * step;
    if (integers) {
      out.emplace_back(std::lround(v));
    } else {
      out.emplace_back(round_sig(v));
    }
  }
  return out;
}

SweepSpec sweep_spec_from_json(const nlohmann::json& j) {
  if (!j.is_object()) throw InputError("sweep: must be a JSON object");
  check_keys(j);
  SweepSpec s;
  s.job = job_spec_from_json(j.at("job"), "sweep.job");
  const auto& table = s.job.generator->table();
  for (const auto& [k, v] : s.job.params.items()) {
    if (!find_def(table, k)) {
      throw InputError("sweep.job.params." + k + ": unknown parameter of " + s.job.generator->name + " (" +
                       table_keys(table) + ")");
    }
  }
  for (const auto& [k, v] : j.at("vary").items()) {
    if (!find_def(table, k)) {
      throw InputError("sweep.vary." + k + ": unknown parameter of " + s.job.generator->name + " (" +
                       table_keys(table) + ")");
    }
    s.keys.push_back(k);
    s.values.push_back(vary_values(v, "sweep.vary." + k));
  }
  const std::string mode = slicer::get_text(j, "mode", "sweep", "product");
  if (mode != "product" && mode != "zip") throw InputError("sweep.mode = " + mode + ": must be product or zip");
  s.mode = mode == "zip" ? SweepMode::Zip : SweepMode::Product;
  for (std::size_t k = 1; s.mode == SweepMode::Zip && k < s.keys.size(); ++k) {
    if (s.values[k].size() != s.values[0].size()) {
      throw InputError("sweep.vary." + s.keys[k] + ": " + std::to_string(s.values[k].size()) +
                       " values, but zip needs as many as sweep.vary." + s.keys[0] + " (" +
                       std::to_string(s.values[0].size()) + ")");
    }
  }
  s.where = parse_where(j.value("where", nlohmann::json::array()), s);
  const std::string out = s.job.settings.output;
  s.stem = out.empty() ? s.job.generator->name : std::filesystem::path(out).stem().string();
  return s;
}

std::vector<SweepPoint> expand_points(const SweepSpec& s) {
  std::size_t total = s.mode == SweepMode::Zip ? s.values[0].size() : 1;
  for (std::size_t k = 0; s.mode == SweepMode::Product && k < s.keys.size(); ++k) {
    total *= s.values[k].size();
    if (total > kMaxPoints) throw InputError("sweep.vary: more than 100000 points");
  }
  std::vector<SweepPoint> points;
  std::set<std::string> names;
  bool any_kept = false;
  for (std::size_t i = 0; i < total; ++i) {
    SweepPoint p;
    p.index = static_cast<int>(i);
    p.params = s.job.params;
    p.varied = nlohmann::json::object();
    p.name = s.stem;
    std::size_t rest = i;
    for (std::size_t k = s.keys.size(); k-- > 0;) {
      const std::size_t n = s.values[k].size();
      const std::size_t at = s.mode == SweepMode::Zip ? i : rest % n;
      rest /= n;
      p.varied[s.keys[k]] = s.values[k][at];
      p.params[s.keys[k]] = s.values[k][at];
    }
    for (const auto& k : s.keys) p.name += "_" + k + "-" + name_text(p.varied[k]);
    if (!names.insert(p.name).second) {
      throw InputError("sweep.vary: two points are both " + p.name + " (a value is listed twice)");
    }
    apply_where(s, p);
    any_kept = any_kept || p.dropped.empty();
    points.push_back(std::move(p));
  }
  if (!any_kept) throw InputError("sweep.where: drops every one of the " + std::to_string(total) + " points (empty sweep)");
  return points;
}

Shard parse_shard(const std::string& text) {
  Shard s;
  const auto slash = text.find('/');
  const char* b = text.data();
  const char* e = text.data() + text.size();
  bool ok = slash != std::string::npos;
  if (ok) {
    auto r1 = std::from_chars(b, b + slash, s.index);
    auto r2 = std::from_chars(b + slash + 1, e, s.count);
    ok = r1.ec == std::errc() && r1.ptr == b + slash && r2.ec == std::errc() && r2.ptr == e;
  }
  if (!ok || s.count < 1 || s.index < 1 || s.index > s.count) {
    throw InputError("--shard = " + text + ": must be I/N with 1 <= I <= N (e.g. 2/8 for task 2 of 8)");
  }
  return s;
}

bool in_shard(int point_index, const Shard& shard) { return point_index % shard.count == shard.index - 1; }

}  // namespace strand::jobs
