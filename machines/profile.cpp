// Loading and validating machine profiles.
#include "machines/profile.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <mutex>

#include "machines/builtin_profiles.h"
#include "machines/profile_schema.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"
#include "slicer/json_input.h"
#include "slicer/units.h"

namespace strand::machines {

namespace {

Vec3 vec3(const nlohmann::json& j) { return Vec3(j[0].get<double>(), j[1].get<double>(), j[2].get<double>()); }
Vec2 vec2(const nlohmann::json& j) { return Vec2(j[0].get<double>(), j[1].get<double>()); }

std::vector<std::string> lines(const nlohmann::json& j, const char* key) {
  if (!j.contains(key)) return {};
  return j.at(key).get<std::vector<std::string>>();
}

BuildVolume read_volume(const nlohmann::json& k, const std::string& origin,
                        std::vector<std::string>& problems) {
  BuildVolume v;
  if (k.at("type") == "delta") {
    v.kind = KinematicsKind::Delta;
    if (!k.contains("radius_mm")) problems.push_back(origin + ": kinematics.radius_mm: missing (required for delta)");
    if (!k.contains("height_mm")) problems.push_back(origin + ": kinematics.height_mm: missing (required for delta)");
    v.radius_mm = k.value("radius_mm", 0.0);
    v.height_mm = k.value("height_mm", 0.0);
    v.part_center_mm = Vec2::Zero();
    v.min_mm = Vec3(-v.radius_mm, -v.radius_mm, 0.0);
    v.max_mm = Vec3(v.radius_mm, v.radius_mm, v.height_mm);
  } else if (k.at("type") == "robot-holds-substrate") {
    v.kind = KinematicsKind::RobotHoldsSubstrate;  // the robot cell's reach replaces a volume
  } else {
    v.kind = k.at("type") == "rotary" ? KinematicsKind::Rotary : KinematicsKind::Cartesian;
    if (!k.contains("min_mm") || !k.contains("max_mm")) {
      problems.push_back(origin + ": kinematics.min_mm/max_mm: missing (required for " +
                         k.at("type").get<std::string>() + ")");
      return v;
    }
    v.min_mm = vec3(k.at("min_mm"));
    v.max_mm = vec3(k.at("max_mm"));
    for (int i = 0; i < 3; ++i) {
      if (v.max_mm[i] <= v.min_mm[i]) {
        problems.push_back(origin + ": kinematics.max_mm: must exceed min_mm on every axis");
        break;
      }
    }
    v.height_mm = v.max_mm.z() - v.min_mm.z();
    v.part_center_mm = k.contains("part_center_mm")
                           ? vec2(k.at("part_center_mm"))
                           : Vec2((v.min_mm.x() + v.max_mm.x()) / 2, (v.min_mm.y() + v.max_mm.y()) / 2);
  }
  return v;
}

DepositionModel model_from(const std::string& s) {
  if (s == "manual-valve") return DepositionModel::ManualValve;
  if (s == "valve") return DepositionModel::Valve;
  if (s == "e-volumetric") return DepositionModel::EVolumetric;
  return DepositionModel::None;
}

Deposition read_deposition(const nlohmann::json& d, const std::string& origin,
                           std::vector<std::string>& problems) {
  Deposition out;
  out.model = model_from(d.at("model").get<std::string>());
  out.lead_s = d.value("lead_s", 0.0);
  out.lag_s = d.value("lag_s", 0.0);
  out.message = d.value("message", std::string());
  out.on_gcode = lines(d, "on_gcode");
  out.off_gcode = lines(d, "off_gcode");
  out.pressure_command = lines(d, "pressure_command");
  out.relative_e = d.value("relative_e", false);
  out.prime_e = d.value("prime_e", 0.0);
  out.retract_e = d.value("retract_e", 0.0);
  out.reservoir_ml = d.value("reservoir_ml", 30.0);
  out.extrude_max_length = d.value("extrude_max_length", out.extrude_max_length);
  if (d.contains("filament_diameter_mm")) {
    const double fd = d.at("filament_diameter_mm").get<double>();
    out.mm3_per_e = slicer::kPi * fd * fd / 4.0;
  }
  out.mm3_per_e = d.value("mm3_per_e", out.mm3_per_e);
  if (out.model == DepositionModel::EVolumetric && !d.contains("mm3_per_e") &&
      !d.contains("filament_diameter_mm")) {
    problems.push_back(origin + ": deposition.mm3_per_e: missing (e-volumetric needs mm3_per_e or filament_diameter_mm)");
  }
  if (!out.pressure_command.empty() && out.model != DepositionModel::Valve &&
      out.model != DepositionModel::ManualValve) {
    problems.push_back(origin + ": deposition.pressure_command: only for valve or manual-valve (E-driven machines set flow by E)");
  }
  for (const std::string& line : out.pressure_command) {
    if (line.find("{flow}") == std::string::npos) {
      problems.push_back(origin + ": deposition.pressure_command: \"" + line + "\" lacks {flow} (the value to set)");
      break;
    }
  }
  if (out.model == DepositionModel::Valve && (out.on_gcode.empty() || out.off_gcode.empty())) {
    problems.push_back(origin + ": deposition.on_gcode/off_gcode: missing (required for valve)");
  }
  return out;
}

// "tools" and "tool_change_gcode" (issue 33): per tool its name, offset, nozzle and
// deposition (the machine's unless given).
void read_tools(const nlohmann::json& j, MachineProfile& p, const std::string& origin, std::vector<std::string>& problems) {
  p.tool_change_gcode = lines(j, "tool_change_gcode");
  if (!j.contains("tools")) {
    if (!p.tool_change_gcode.empty()) problems.push_back(origin + ": tool_change_gcode: only with a tools list");
    return;
  }
  const auto& tools = j.at("tools");
  for (std::size_t k = 0; k < tools.size(); ++k) {
    const auto& t = tools[k];
    Tool tool;
    tool.name = t.at("name").get<std::string>();
    if (t.contains("offset_mm")) {
      const auto& o = t.at("offset_mm");
      tool.offset_mm = Vec3(o[0].get<double>(), o[1].get<double>(), o[2].get<double>());
    }
    tool.nozzle_mm = t.value("nozzle_mm", 0.0);
    tool.idle_lift_mm = t.value("idle_lift_mm", 0.0);
    tool.temperature_c = t.value("temperature_c", 0.0);
    tool.select_gcode = lines(t, "select_gcode");
    tool.deselect_gcode = lines(t, "deselect_gcode");
    if (p.firmware == Firmware::Grbl && tool.temperature_c > 0) {
      problems.push_back(origin + ": tools[" + std::to_string(k) + "].temperature_c: GRBL has no heater commands");
    }
    tool.deposition = t.contains("deposition")
                          ? read_deposition(t.at("deposition"), origin + ": tools[" + std::to_string(k) + "]", problems)
                          : p.deposition;
    if (p.firmware == Firmware::Grbl && tool.deposition.model == DepositionModel::EVolumetric) {
      problems.push_back(origin + ": tools[" + std::to_string(k) + "].deposition.model = \"e-volumetric\": GRBL has no E axis");
    }
    p.tools.push_back(std::move(tool));
  }
  if (!p.tools.empty() && p.tools[0].offset_mm.norm() > 0) {
    problems.push_back(origin + ": tools[0].offset_mm: must be [0, 0, 0] (offsets are from the first tool)");
  }
  if (p.firmware == Firmware::Grbl && p.tool_change_gcode.empty()) {
    problems.push_back(origin + ": tool_change_gcode: missing (GRBL has no T command; give the machine's own)");
  }
}

Firmware firmware_from(const std::string& s) {
  if (s == "reprap") return Firmware::RepRap;
  if (s == "klipper") return Firmware::Klipper;
  if (s == "grbl") return Firmware::Grbl;
  return Firmware::Marlin;
}

}  // namespace

std::string to_string(Firmware f) {
  switch (f) {
    case Firmware::Marlin: return "marlin";
    case Firmware::RepRap: return "reprap";
    case Firmware::Klipper: return "klipper";
    case Firmware::Grbl: return "grbl";
  }
  return "";
}

std::string to_string(KinematicsKind k) {
  switch (k) {
    case KinematicsKind::Delta: return "delta";
    case KinematicsKind::Cartesian: return "cartesian";
    case KinematicsKind::RobotHoldsSubstrate: return "robot-holds-substrate";
    case KinematicsKind::Rotary: return "rotary";
  }
  return "";
}

std::string to_string(DepositionModel m) {
  switch (m) {
    case DepositionModel::ManualValve: return "manual-valve";
    case DepositionModel::Valve: return "valve";
    case DepositionModel::EVolumetric: return "e-volumetric";
    case DepositionModel::None: return "none";
  }
  return "";
}

int tool_count(const MachineProfile& m) { return m.tools.empty() ? 1 : static_cast<int>(m.tools.size()); }

const Deposition& tool_deposition(const MachineProfile& m, int tool) {
  if (m.tools.empty() || tool < 0 || tool >= static_cast<int>(m.tools.size())) return m.deposition;
  return m.tools[static_cast<std::size_t>(tool)].deposition;
}

Vec3 tool_offset(const MachineProfile& m, int tool) {
  if (m.tools.empty() || tool < 0 || tool >= static_cast<int>(m.tools.size())) return Vec3::Zero();
  return m.tools[static_cast<std::size_t>(tool)].offset_mm;
}

MachineProfile profile_from_json(const nlohmann::json& j, const std::string& origin) {
  std::vector<std::string> problems = check_profile_schema(j, origin);
  if (!problems.empty()) throw InputError(problems);
  MachineProfile p;
  p.name = j.at("name").get<std::string>();
  p.description = j.at("description").get<std::string>();
  p.volume = read_volume(j.at("kinematics"), origin, problems);
  p.firmware = firmware_from(j.at("firmware").at("flavour").get<std::string>());
  p.arcs = j.at("firmware").at("arcs").get<bool>();
  p.deposition = read_deposition(j.at("deposition"), origin, problems);
  const auto lim = j.value("limits", nlohmann::json::object());
  p.limits.max_feed_mm_per_min = lim.value("max_feed_mm_per_min", p.limits.max_feed_mm_per_min);
  p.limits.travel_feed_mm_per_min = lim.value("travel_feed_mm_per_min", p.limits.travel_feed_mm_per_min);
  p.limits.z_feed_mm_per_min = lim.value("z_feed_mm_per_min", p.limits.z_feed_mm_per_min);
  p.limits.acceleration_mm_per_s2 = lim.value("acceleration_mm_per_s2", p.limits.acceleration_mm_per_s2);
  p.limits.junction_deviation_mm = lim.value("junction_deviation_mm", p.limits.junction_deviation_mm);
  p.limits.max_volumetric_flow_mm3_per_s =
      lim.value("max_volumetric_flow_mm3_per_s", p.limits.max_volumetric_flow_mm3_per_s);
  const auto factors = j.value("speed_factors", nlohmann::json::object());
  for (const auto& [k, v] : factors.items()) {
    p.speed_factors[slicer::feature_from_string(k)] = v.get<double>();
  }
  if (p.firmware == Firmware::Grbl && p.deposition.model == DepositionModel::EVolumetric) {
    problems.push_back(origin + ": deposition.model = \"e-volumetric\": GRBL has no E axis (use valve or none)");
  }
  p.travel_lift_mm = j.value("travel_lift_mm", p.travel_lift_mm);
  p.max_surface_slope_deg = j.value("max_surface_slope_deg", p.max_surface_slope_deg);
  p.start_gcode = lines(j, "start_gcode");
  p.end_gcode = lines(j, "end_gcode");
  read_tools(j, p, origin, problems);
  p.source = j;
  p.plotter = read_plotter(j, origin, problems);  // plotting (issue 5)
  p.robot = read_robot_cell(j, origin, problems);  // curved substrates (issue 11)
  p.rotary = read_rotary_axis(j, origin, problems);
  if (!problems.empty()) throw InputError(problems);
  return p;
}

std::string user_profile_dir() {
  const char* xdg = std::getenv("XDG_CONFIG_HOME");
  if (xdg && *xdg == '/') return std::string(xdg) + "/strand/machines";
  const char* home = std::getenv("HOME");
  if (home && *home) return std::string(home) + "/.config/strand/machines";
  return "";
}

namespace {

// The user's file for a profile name, "" when there is none. Names are plain file stems
// (no path separators, no leading dot), so a name never reaches outside the directory.
std::string user_profile_file(const std::string& name) {
  const auto dir = user_profile_dir();
  if (dir.empty() || name.empty() || name[0] == '.' || name.find('/') != std::string::npos) {
    return "";
  }
  const std::string path = dir + "/" + name + ".json";
  std::error_code ec;
  return std::filesystem::is_regular_file(path, ec) ? path : "";
}

}  // namespace

namespace {
// Profiles kept parsed (a few kilobytes each); the cache starts over when full.
constexpr std::size_t kProfileCacheEntries = 32;
}  // namespace

MachineProfile load_profile(const std::string& name_or_path) {
  const bool is_path = name_or_path.find('/') != std::string::npos ||
                       (name_or_path.size() > 5 && name_or_path.ends_with(".json"));
  std::string text;
  if (is_path) {
    try {
      text = slicer::read_file(name_or_path);
    } catch (const InputError&) {
      throw InputError("machine = " + name_or_path + ": cannot read the profile file");
    }
  } else if (const auto user = user_profile_file(name_or_path); !user.empty()) {
    text = slicer::read_file(user);
  } else {
    const auto& all = builtin_profiles();
    auto it = std::find_if(all.begin(), all.end(),
                           [&](const BuiltinProfile& b) { return name_or_path == b.name; });
    if (it == all.end()) {
      std::string names;
      for (const auto& b : all) names += (names.empty() ? "" : ", ") + std::string(b.name);
      throw InputError("machine = " + name_or_path + ": unknown machine (one of " + names +
                       ", or a path to a .json profile)");
    }
    text = it->json;
  }
  // A sweep loads the same profile for every point: the parsed and checked profile is kept,
  // keyed by the name and the exact text read (an edited file is read anew).
  static std::mutex cache_mutex;
  static std::map<std::string, MachineProfile> cache;
  const std::string key = name_or_path + '\0' + text;
  {
    const std::lock_guard<std::mutex> lock(cache_mutex);
    if (const auto hit = cache.find(key); hit != cache.end()) return hit->second;
  }
  const nlohmann::json j = slicer::parse_json(text, "machine = " + name_or_path);
  MachineProfile profile = profile_from_json(j, "machine " + name_or_path);
  const std::lock_guard<std::mutex> lock(cache_mutex);
  if (cache.size() >= kProfileCacheEntries) cache.clear();
  cache.emplace(key, profile);
  return profile;
}

std::vector<ProfileEntry> profile_catalog() {
  std::map<std::string, ProfileEntry> by_name;
  for (const auto& b : builtin_profiles()) {
    const auto j = nlohmann::json::parse(b.json);
    by_name[b.name] = {b.name, j.value("description", std::string()), "shipped", false, b.json};
  }
  const auto dir = user_profile_dir();
  std::error_code ec;
  if (!dir.empty() && std::filesystem::is_directory(dir, ec)) {
    std::vector<std::filesystem::path> files;
    for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
      if (files.size() == 1000) break;
      if (e.path().extension() == ".json" && !user_profile_file(e.path().stem().string()).empty()) {
        files.push_back(e.path());
      }
    }
    std::sort(files.begin(), files.end());
    for (const auto& f : files) {
      const std::string name = f.stem().string();
      ProfileEntry entry{name, "", f.string(), by_name.count(name) > 0, ""};
      try {
        entry.json_text = slicer::read_file(f.string());
        const auto j = slicer::parse_json(entry.json_text, f.string());
        entry.description =
            j.is_object() ? j.value("description", std::string()) : "not a JSON object";
      } catch (const std::exception& e) {
        entry.description = e.what();
      }
      by_name[name] = entry;
    }
  }
  std::vector<ProfileEntry> out;
  for (auto& [name, entry] : by_name) out.push_back(std::move(entry));
  return out;
}

std::vector<std::pair<std::string, std::string>> list_profiles() {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& b : builtin_profiles()) {
    const auto j = nlohmann::json::parse(b.json);
    out.emplace_back(b.name, j.value("description", std::string()));
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace strand::machines
