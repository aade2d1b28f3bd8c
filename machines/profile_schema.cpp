// Schema for machine profile JSON, checked before any value is used.
#include "machines/profile_schema.h"

#include <optional>
#include <utility>

#include "slicer/params.h"

namespace strand::machines {

namespace {

enum class T { Number, Bool, String, StringList, NumberList, Vec2, Vec3, Object, FreeObject, ObjectList };

struct Field {
  const char* key;
  T type;
  bool required = false;
  std::optional<double> min = std::nullopt;
  std::optional<double> max = std::nullopt;
  std::vector<std::string> choices = {};
  std::vector<Field> children = {};
};

// An object field: its keys are checked against `children`.
Field object(const char* key, bool required, std::vector<Field> children) {
  return {key, T::Object, required, std::nullopt, std::nullopt, {}, std::move(children)};
}

// clang-format off
// The deposition object's keys: the machine's, and each tool's own.
std::vector<Field> deposition_fields() {
  return {
      {"model", T::String, true, {}, {}, {"manual-valve", "valve", "e-volumetric", "none"}},
      {"lead_s", T::Number, false, 0.0, 600.0},
      {"lag_s", T::Number, false, 0.0, 60.0},
      {"message", T::String},
      {"on_gcode", T::StringList},
      {"off_gcode", T::StringList},
      {"pressure_command", T::StringList},
      {"mm3_per_e", T::Number, false, 1e-6, 1e6},
      {"filament_diameter_mm", T::Number, false, 0.1, 100.0},
      {"relative_e", T::Bool},
      {"prime_e", T::Number, false, 0.0, 1000.0},
      {"retract_e", T::Number, false, 0.0, 100.0},
      {"reservoir_ml", T::Number, false, 0.1, 100000.0},
      {"extrude_max_length", T::Number, false, 1.0, 1e6},
  };
}

// A list of objects (the tools): each element's keys checked against `children`.
Field object_list(const char* key, std::vector<Field> children) {
  return {key, T::ObjectList, false, 1.0, 16.0, {}, std::move(children)};
}
// clang-format on

// One line per key; an object's keys indented below it (kept so: clang-format would spread
// each object call over its own indentation).
// clang-format off
const std::vector<Field>& schema() {
  static const std::vector<Field> kSchema = {
      {"name", T::String, true},
      {"description", T::String, true},
      {"sources", T::FreeObject},
      object("kinematics", true, {
          {"type", T::String, true, {}, {},
           {"delta", "cartesian", "robot-holds-substrate", "rotary"}},
          {"radius_mm", T::Number, false, 1.0, 10000.0},
          {"height_mm", T::Number, false, 1.0, 10000.0},
          {"min_mm", T::Vec3},
          {"max_mm", T::Vec3},
          {"part_center_mm", T::Vec2},
      }),
      object("firmware", true, {
          {"flavour", T::String, true, {}, {}, {"marlin", "reprap", "klipper", "grbl"}},
          {"arcs", T::Bool, true},
      }),
      object("deposition", true, deposition_fields()),
      object_list("tools", {  // several printheads (issue 33)
          {"name", T::String, true},
          {"offset_mm", T::Vec3, false, -1000.0, 1000.0},
          {"nozzle_mm", T::Number, false, 0.01, 20.0},
          {"idle_lift_mm", T::Number, false, 0.0, 100.0},
          {"temperature_c", T::Number, false, 1.0, 400.0},
          {"select_gcode", T::StringList},
          {"deselect_gcode", T::StringList},
          object("deposition", false, deposition_fields()),
      }),
      {"tool_change_gcode", T::StringList},
      object("limits", false, {
          {"max_feed_mm_per_min", T::Number, false, 1.0, 1e6},
          {"travel_feed_mm_per_min", T::Number, false, 1.0, 1e6},
          {"z_feed_mm_per_min", T::Number, false, 1.0, 1e6},
          {"acceleration_mm_per_s2", T::Number, false, 1.0, 1e6},
          {"junction_deviation_mm", T::Number, false, 0.0, 10.0},
          {"max_volumetric_flow_mm3_per_s", T::Number, false, 0.0, 1e5},
      }),
      object("speed_factors", false, {
          {"infill", T::Number, false, 0.05, 10.0},
          {"wall", T::Number, false, 0.05, 10.0},
          {"ligament", T::Number, false, 0.05, 10.0},
          {"node", T::Number, false, 0.05, 10.0},
          {"grip", T::Number, false, 0.05, 10.0},
          {"frame", T::Number, false, 0.05, 10.0},
          {"link", T::Number, false, 0.05, 10.0},
          {"pen", T::Number, false, 0.05, 10.0},
      }),
      {"travel_lift_mm", T::Number, false, 0.0, 100.0},
      {"max_surface_slope_deg", T::Number, false, 0.0, 89.0},
      {"start_gcode", T::StringList},
      {"end_gcode", T::StringList},
      // --- curved substrates (issue 11): robot cell, its extruder, rotary axis ---
      object("robot", false, {
          {"arm", T::String, true, {}, {}, {"lbr-iiwa-14-r820", "ur10e", "irb1200-5-0.9"}},
          {"v_cart_mm_per_s", T::Number, false, 0.1, 1000.0},
          {"travel_speed_mm_per_s", T::Number, false, 0.1, 1000.0},
          {"lift_mm", T::Number, false, 0.0, 100.0},
          {"joint_limits_deg", T::NumberList},
          {"joint_min_deg", T::NumberList},
          {"joint_limit_margin_deg", T::Number, false, 0.0, 45.0},
          {"reach_mm", T::Number, false, 1.0, 10000.0},
          {"nozzle_tip_mm", T::Vec3, true},
          {"nozzle_axis", T::Vec3, true},
          {"substrate_axis", T::Vec3, true},
          {"mount_mm", T::Number, false, 0.0, 2000.0},
          {"mount_rotation_deg", T::Number, false, -360.0, 360.0},
          object("sunrise", false, {
              {"io_group", T::String},
              {"lap_signal", T::String},
              {"ready_signal", T::String},
              {"csv_dir", T::String},
              {"tool_template", T::String},
              {"tool_frame", T::String},
              {"nozzle_frame", T::String},
          }),
          object("krl", false, {
              {"tool_data", T::Number, false, 1.0, 16.0},
              {"base_data", T::Number, false, 1.0, 32.0},
              {"tool_index", T::Number},  // former keys, refused with a hint when read
              {"base_index", T::Number},
              {"lap_output", T::Number, false, 1.0, 4096.0},
              {"points_per_module", T::Number, false, 10.0, 100000.0},
              {"ready_input", T::Number, false, 0.0, 4096.0},
          }),
          object("urscript", false, {
              {"lap_output", T::Number, false, 0.0, 7.0},
              {"ready_input", T::Number, false, -1.0, 7.0},
              {"acceleration_mm_per_s2", T::Number, false, 1.0, 10000.0},
          }),
          object("rapid", false, {
              {"tool", T::String},
              {"wobj", T::String},
              {"lap_signal", T::String},
              {"ready_signal", T::String},
              {"tool_on_controller", T::Bool},
              {"wobj_on_controller", T::Bool},
          }),
          {"acceleration_mm_per_s2", T::Number, false, 1.0, 100000.0},
          {"approach_mm", T::Number, false, 0.0, 500.0},
          {"retract_mm", T::Number, false, 0.0, 500.0},
          {"clearance_mm", T::Number, false, 0.0, 1000.0},
          {"transit_margin_mm", T::Number, false, 0.0, 200.0},
          {"home_joints_deg", T::NumberList},
          {"ptp_velocity_percent", T::Number, false, 1.0, 100.0},
          object("load", false, {
              {"mass_kg", T::Number, false, 0.0, 100.0},
              {"cog_mm", T::Vec3},
          }),
          object("nozzle_cone", false, {  // the nozzle's outside, checked against a substrate mesh
              {"half_angle_deg", T::Number, false, 0.0, 89.0},
              {"length_mm", T::Number, false, 0.0, 1000.0},
              {"tip_radius_mm", T::Number, false, 0.0, 100.0},
          }),
          object("keep_out", false, {  // the extruder's body above the cone, about the nozzle axis
              {"radius_mm", T::Number, false, 0.0, 1000.0},
              {"length_mm", T::Number, false, 0.0, 5000.0},
          }),
      }),
      object("extruder", false, {
          {"park_mm", T::Vec3, true},
          {"park_feed_mm_per_min", T::Number, false, 1.0, 1e6},
          {"v_ext_mm_per_min", T::Number, false, 0.01, 1e5},
          {"e_per_mm", T::String, false, {}, {}, {"time-based", "volumetric"}},
          {"handshake_pin", T::Number, false, -1.0, 1000.0},
          {"handshake_state", T::Number, false, 0.0, 1.0},
          {"ready_pin", T::Number, false, -1.0, 1000.0},
      }),
      object("rotary", false, {
          {"axis", T::String, true, {}, {}, {"A", "B"}},
          {"axis_dir", T::Vec3, true},
          {"axis_point_mm", T::Vec3, true},
          {"max_radius_mm", T::Number, false, 0.1, 10000.0},
          {"lift_mm", T::Number, false, 0.0, 100.0},
          {"feed", T::String, false, {}, {}, {"xyz-distance", "inverse-time"}},
      }),
      // --- plotting (issue 5): plotter kinematics and pen handling ---
      object("plotter", false, {
          {"kinematics", T::String, true, {}, {}, {"xy", "polargraph", "polar-rtheta"}},
          {"motor_distance_mm", T::Number, false, 10.0, 100000.0},
          {"gondola_width_mm", T::Number, false, 0.0, 10000.0},
          {"pen_offset_mm", T::Number, false, -10000.0, 10000.0},
          {"min_tension", T::Number, false, 0.0, 100.0},
          {"max_tension", T::Number, false, 0.01, 100.0},
          {"max_resolution_loss", T::Number, false, 1.0, 100.0},
          {"home_mm", T::Vec2},
          {"pivot_mm", T::Vec2},
          {"lever_mm", T::Number, false, 1.0, 100000.0},
          {"origin_radius_mm", T::Number, false, 1.0, 100000.0},
          {"steps_per_mm", T::Vec2, false, 1e-6, 1e9},
      }),
      object("pen", false, {
          {"lift", T::String, true, {}, {}, {"servo", "z", "drum"}},
          {"count", T::Number, false, 1.0, 64.0},
          {"width_mm", T::Number, false, 0.01, 50.0},
          {"capacity_mm", T::Number, false, 0.0, 1e9},
          {"pause_on_empty", T::Bool},
          {"change_gcode", T::StringList},
          {"servo_index", T::Number, false, 0.0, 16.0},
          {"up_value", T::Number, false, 0.0, 100000.0},
          {"down_value", T::Number, false, 0.0, 100000.0},
          {"dwell_s", T::Number, false, 0.0, 10.0},
          {"z_up_mm", T::Number, false, -1000.0, 1000.0},
          {"z_down_mm", T::Number, false, -1000.0, 1000.0},
          {"draw_feed_mm_per_min", T::Number, false, 1.0, 1e6},
          object("drum", false, {
              {"engage_step_deg", T::Number, false, 1.0, 90.0},
              {"rest_offset_deg", T::Number, false, 0.0, 90.0},
              {"write_offset_deg", T::Number, false, 0.0, 90.0},
          }),
          object("erase", false, {
              {"disc_diameter_mm", T::Number, false, 1.0, 1000.0},
              {"offset_mm", T::Vec2},
              {"temperature_c", T::Number, false, 0.0, 500.0},
              {"dwell_s", T::Number, false, 0.0, 600.0},
              {"feed_mm_per_min", T::Number, false, 1.0, 1e6},
          }),
      }),
  };
  return kSchema;
}
// clang-format on

const char* type_rule(T t) {
  switch (t) {
    case T::Number:
      return "must be a number";
    case T::Bool:
      return "must be true or false";
    case T::String:
      return "must be a string";
    case T::StringList:
      return "must be a list of strings";
    case T::NumberList:
      return "must be a list of numbers";
    case T::Vec2:
      return "must be [x, y] in mm";
    case T::Vec3:
      return "must be [x, y, z] in mm";
    case T::Object:
    case T::FreeObject:
      return "must be an object";
    case T::ObjectList:
      return "must be a list of 1 to 16 objects";
  }
  return "";
}

bool numbers(const nlohmann::json& v, std::size_t n) {
  if (!v.is_array() || v.size() != n) return false;
  for (const auto& e : v) {
    if (!e.is_number()) return false;
  }
  return true;
}

bool type_ok(T t, const nlohmann::json& v) {
  switch (t) {
    case T::Number:
      return v.is_number();
    case T::Bool:
      return v.is_boolean();
    case T::String:
      return v.is_string();
    case T::StringList:
      if (!v.is_array()) return false;
      for (const auto& e : v) {
        if (!e.is_string()) return false;
      }
      return true;
    case T::NumberList:
      return numbers(v, v.is_array() ? v.size() : 0) && !v.empty();
    case T::Vec2:
      return numbers(v, 2);
    case T::Vec3:
      return numbers(v, 3);
    case T::Object:
    case T::FreeObject:
      return v.is_object();
    case T::ObjectList:
      if (!v.is_array() || v.empty() || v.size() > 16) return false;
      for (const auto& e : v) {
        if (!e.is_object()) return false;
      }
      return true;
  }
  return false;
}

std::string shown(const nlohmann::json& v) {
  return v.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

// Profile text reaches G-code (names in the header, templates, valve commands): one line
// each, no control characters, so a profile cannot slip extra lines into a file.
bool one_line(const nlohmann::json& v) {
  if (v.is_array()) {
    for (const auto& e : v) {
      if (!one_line(e)) return false;
    }
    return true;
  }
  if (!v.is_string()) return true;
  for (const char c : v.get_ref<const std::string&>()) {
    const auto u = static_cast<unsigned char>(c);
    if ((u < 0x20 && c != '\t') || u == 0x7f) return false;
  }
  return true;
}

bool in_range(const Field& f, const nlohmann::json& v) {
  if (v.is_array()) {
    for (const auto& e : v) {
      if (!in_range(f, e)) return false;
    }
    return true;
  }
  const double x = v.get<double>();
  return !(f.min && x < *f.min) && !(f.max && x > *f.max);
}

void check(const std::vector<Field>& fields, const nlohmann::json& j, const std::string& prefix,
           const std::string& origin, std::vector<std::string>& out) {
  for (const auto& [key, value] : j.items()) {
    bool known = false;
    for (const auto& f : fields) known = known || key == f.key;
    if (!known) out.push_back(origin + ": " + prefix + key + ": unknown key");
  }
  for (const auto& f : fields) {
    const std::string path = prefix + f.key;
    if (!j.contains(f.key)) {
      if (f.required) out.push_back(origin + ": " + path + ": missing (required)");
      continue;
    }
    const auto& v = j.at(f.key);
    if (!type_ok(f.type, v)) {
      out.push_back(origin + ": " + path + " = " + shown(v) + ": " + type_rule(f.type));
      continue;
    }
    if (!one_line(v)) {
      out.push_back(origin + ": " + path + ": must be one line of text without control characters");
      continue;
    }
    const bool numeric = f.type == T::Number || f.type == T::Vec2 || f.type == T::Vec3;
    if (numeric && (f.min || f.max) && !in_range(f, v)) {
      out.push_back(origin + ": " + path + " = " + shown(v) + ": must be in [" +
                    slicer::short_number(f.min.value_or(-1e300)) + ", " +
                    slicer::short_number(f.max.value_or(1e300)) + "]" +
                    (f.type == T::Number ? "" : " each"));
    }
    if (f.type == T::String && !f.choices.empty()) {
      bool ok = false;
      std::string list;
      for (const auto& c : f.choices) {
        ok = ok || c == v.get<std::string>();
        list += (list.empty() ? "" : ", ") + c;
      }
      if (!ok) out.push_back(origin + ": " + path + " = " + shown(v) + ": must be one of " + list);
    }
    if (f.type == T::Object) check(f.children, v, path + ".", origin, out);
    if (f.type == T::ObjectList) {
      for (std::size_t k = 0; k < v.size(); ++k) check(f.children, v[k], path + "[" + std::to_string(k) + "].", origin, out);
    }
  }
}

}  // namespace

std::vector<std::string> check_profile_schema(const nlohmann::json& j, const std::string& origin) {
  std::vector<std::string> out;
  if (!j.is_object()) return {origin + ": the profile must be a JSON object"};
  check(schema(), j, "", origin, out);
  return out;
}

}  // namespace strand::machines
