// Reading a scaffold schedule: each entry's values are checked against a parameter table
// (units and ranges as on the command line), its layers against the stack.
#include "patterns/scaffold_schedule.h"

#include <algorithm>
#include <charconv>

#include "slicer/input_error.h"
#include "slicer/params.h"

namespace strand::patterns {

namespace {

using slicer::ParamType;

slicer::ParamTable entry_table(const std::string& name) {
  return {name,
          {
              {"layers", ParamType::Text, "", "layer range FIRST-LAST or one layer, 0-based"},
              {"speed", ParamType::Number, "mm/min", "print speed", 0.0, true, 100000.0},
              {"flow", ParamType::Number, "", "bead section relative to a nozzle-wide bead", 0.2, false, 5.0},
              {"gap", ParamType::Number, "mm", "edge-to-edge gap between filaments", 0.0, false, 100.0},
              {"angle", ParamType::Number, "deg", "lay-down angle", -360.0, false, 360.0},
          }};
}

bool read_int(std::string_view text, int& out) {
  const auto r = std::from_chars(text.data(), text.data() + text.size(), out);
  return r.ec == std::errc() && r.ptr == text.data() + text.size() && !text.empty();
}

// "3" or "0-4" (spaces allowed around the dash); false if neither.
bool read_range(const nlohmann::json& v, int& first, int& last) {
  if (v.is_number_integer()) {
    first = last = v.get<int>();
    return true;
  }
  if (!v.is_string()) return false;
  std::string t = v.get<std::string>();
  t.erase(std::remove(t.begin(), t.end(), ' '), t.end());
  const auto dash = t.find('-', 1);
  if (dash == std::string::npos) {
    if (!read_int(t, first)) return false;
    last = first;
    return true;
  }
  return read_int(std::string_view(t).substr(0, dash), first) &&
         read_int(std::string_view(t).substr(dash + 1), last);
}

}  // namespace

std::vector<ScheduleEntry> schedule_from(const nlohmann::json& schedule, int layers,
                                         std::vector<std::string>& problems) {
  std::vector<ScheduleEntry> out;
  if (!schedule.is_array()) {
    problems.push_back("scaffold.schedule: must be a list of entries like {\"layers\": \"0-4\", \"speed\": 300}");
    return out;
  }
  for (std::size_t i = 0; i < schedule.size(); ++i) {
    const nlohmann::json& e = schedule[i];
    const std::string at = "scaffold.schedule[" + std::to_string(i) + "]";
    if (!e.is_object() || !e.contains("layers")) {
      problems.push_back(at + ": must be an object with \"layers\" (e.g. \"0-4\") and any of speed, flow, gap, angle");
      continue;
    }
    ScheduleEntry s;
    const std::string shown = slicer::value_text(e.at("layers"));
    if (!read_range(e.at("layers"), s.first, s.last) || s.first < 0 || s.last < s.first || s.last >= layers) {
      problems.push_back(at + ".layers = " + shown + ": must be FIRST-LAST with 0 <= FIRST <= LAST <= " +
                         std::to_string(layers - 1) + " (the last layer)");
      continue;
    }
    try {
      nlohmann::json given = e;
      given["layers"] = shown;
      const nlohmann::json v = slicer::resolve_params(entry_table("scaffold.schedule[" + shown + "]"), given);
      if (v.size() < 2) problems.push_back(at + ": sets nothing (give speed, flow, gap or angle)");
      if (v.contains("speed")) s.speed_mm_per_min = v.at("speed").get<double>();
      if (v.contains("flow")) s.flow = v.at("flow").get<double>();
      if (v.contains("gap")) s.gap_mm = v.at("gap").get<double>();
      if (v.contains("angle")) s.angle_deg = v.at("angle").get<double>();
    } catch (const InputError& err) {
      problems.push_back(err.what());
      continue;
    }
    out.push_back(s);
  }
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (std::size_t i = 1; i < out.size(); ++i) {
    if (out[i].first <= out[i - 1].last) {
      problems.push_back("scaffold.schedule[" + std::to_string(out[i].first) + "-" + std::to_string(out[i].last) +
                         "].layers: overlaps layers " + std::to_string(out[i - 1].first) + "-" +
                         std::to_string(out[i - 1].last) + " (each layer in one entry at most)");
    }
  }
  return out;
}

}  // namespace strand::patterns
