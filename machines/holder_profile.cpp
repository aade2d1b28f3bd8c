// Reading the robot cell and rotary axis blocks of a profile.
#include "machines/holder_profile.h"

#include <cmath>
#include <utility>

#include "machines/program_text.h"
#include "slicer/input_error.h"

namespace strand::machines {

namespace {

Vec3 vec3_or(const nlohmann::json& j, const char* key, const Vec3& fallback) {
  if (!j.contains(key)) return fallback;
  const auto& v = j.at(key);
  return Vec3(v[0].get<double>(), v[1].get<double>(), v[2].get<double>());
}

// A direction given in the profile, normalised; a zero vector is a problem.
Vec3 direction(const nlohmann::json& j, const char* key, const Vec3& fallback,
               const std::string& where, std::vector<std::string>& problems) {
  const Vec3 v = vec3_or(j, key, fallback);
  if (v.norm() < 1e-9) {
    problems.push_back(where + "." + key + ": must be a non-zero direction");
    return fallback;
  }
  return v.normalized();
}

ExtruderSetup read_extruder(const nlohmann::json& e) {
  ExtruderSetup x;
  x.park_mm = vec3_or(e, "park_mm", x.park_mm);
  x.park_feed_mm_per_min = e.value("park_feed_mm_per_min", x.park_feed_mm_per_min);
  x.v_ext_mm_per_min = e.value("v_ext_mm_per_min", x.v_ext_mm_per_min);
  x.time_based = e.value("e_per_mm", std::string("time-based")) == "time-based";
  x.handshake_pin = e.value("handshake_pin", x.handshake_pin);
  x.handshake_state = e.value("handshake_state", x.handshake_state);
  x.ready_pin = e.value("ready_pin", x.ready_pin);
  return x;
}

RobotPrograms read_programs(const nlohmann::json& r) {
  RobotPrograms p;
  const auto s = r.value("sunrise", nlohmann::json::object());
  p.sunrise_io_group = s.value("io_group", p.sunrise_io_group);
  p.sunrise_lap_signal = s.value("lap_signal", p.sunrise_lap_signal);
  p.sunrise_csv_dir = s.value("csv_dir", p.sunrise_csv_dir);
  p.sunrise_tool_template = s.value("tool_template", p.sunrise_tool_template);
  p.sunrise_tool_frame = s.value("tool_frame", p.sunrise_tool_frame);
  p.sunrise_nozzle_frame = s.value("nozzle_frame", p.sunrise_nozzle_frame);
  const auto k = r.value("krl", nlohmann::json::object());
  p.krl_tool_data = k.value("tool_data", p.krl_tool_data);
  p.krl_base_data = k.value("base_data", p.krl_base_data);
  p.krl_lap_output = k.value("lap_output", p.krl_lap_output);
  p.krl_points_per_module = k.value("points_per_module", p.krl_points_per_module);
  p.sunrise_ready_signal = s.value("ready_signal", p.sunrise_ready_signal);
  p.krl_ready_input = k.value("ready_input", p.krl_ready_input);
  const auto u = r.value("urscript", nlohmann::json::object());
  p.ur_lap_output = u.value("lap_output", p.ur_lap_output);
  p.ur_ready_input = u.value("ready_input", p.ur_ready_input);
  p.ur_acceleration_mm_per_s2 = u.value("acceleration_mm_per_s2", p.ur_acceleration_mm_per_s2);
  const auto a = r.value("rapid", nlohmann::json::object());
  p.rapid_tool = a.value("tool", p.rapid_tool);
  p.rapid_wobj = a.value("wobj", p.rapid_wobj);
  p.rapid_lap_signal = a.value("lap_signal", p.rapid_lap_signal);
  p.rapid_ready_signal = a.value("ready_signal", p.rapid_ready_signal);
  p.rapid_tool_on_controller = a.value("tool_on_controller", p.rapid_tool_on_controller);
  p.rapid_wobj_on_controller = a.value("wobj_on_controller", p.rapid_wobj_on_controller);
  return p;
}

RobotMotionSetup read_motion(const nlohmann::json& r) {
  RobotMotionSetup m;
  m.approach_mm = r.value("approach_mm", m.approach_mm);
  m.retract_mm = r.value("retract_mm", m.retract_mm);
  m.clearance_mm = r.value("clearance_mm", m.clearance_mm);
  m.transit_margin_mm = r.value("transit_margin_mm", m.transit_margin_mm);
  if (r.contains("home_joints_deg")) {
    std::array<double, 7> home{};
    const auto& h = r.at("home_joints_deg");
    for (std::size_t i = 0; i < 7 && i < h.size(); ++i) home[i] = h[i].get<double>();
    m.home_joints_deg = home;
  }
  m.ptp_velocity_percent = r.value("ptp_velocity_percent", m.ptp_velocity_percent);
  const auto load = r.value("load", nlohmann::json::object());
  m.load_mass_kg = load.value("mass_kg", m.load_mass_kg);
  m.load_cog_mm = vec3_or(load, "cog_mm", m.load_cog_mm);
  if (r.contains("acceleration_mm_per_s2"))
    m.path_acceleration_mm_per_s2 = r.at("acceleration_mm_per_s2").get<double>();
  return m;
}

// Controller data the programs name: KRL indices are whole numbers, Sunrise names are checked
// as the Java program uses them, the tool and its frame come together; the former KRL index
// keys (never used) are refused so that nobody relies on them.
void check_controller_data(const nlohmann::json& r, const RobotCell& c, const std::string& where,
                           std::vector<std::string>& problems) {
  const auto k = r.value("krl", nlohmann::json::object());
  for (const char* key : {"tool_data", "base_data"}) {
    if (k.contains(key) && k.at(key).get<double>() != std::floor(k.at(key).get<double>()))
      problems.push_back(where + ".krl." + key + " = " + k.at(key).dump() +
                         ": must be a whole number (the index into " +
                         (std::string(key) == "tool_data" ? "TOOL_DATA" : "BASE_DATA") + ")");
  }
  for (const auto& [old_key, new_key] : {std::pair{"tool_index", "tool_data"},
                                         std::pair{"base_index", "base_data"}}) {
    if (k.contains(old_key))
      problems.push_back(where + ".krl." + old_key + ": no longer read; set robot.krl." +
                         new_key + " to make the program use the controller's " +
                         (std::string(new_key) == "tool_data" ? "TOOL_DATA" : "BASE_DATA") +
                         " (otherwise it uses the profile's frames in the .dat)");
  }
  const RobotPrograms& p = c.programs;
  if (!p.sunrise_tool_template.empty()) {
    try {
      require_sunrise_name(where + ".sunrise.tool_template", p.sunrise_tool_template);
    } catch (const InputError& e) {
      problems.push_back(e.what());
    }
  }
  for (const auto& [key, value] : {std::pair{"tool_frame", p.sunrise_tool_frame},
                                   std::pair{"nozzle_frame", p.sunrise_nozzle_frame}}) {
    if (value.empty()) continue;
    try {
      require_sunrise_frame_path(where + ".sunrise." + key, value);
    } catch (const InputError& e) {
      problems.push_back(e.what());
    }
  }
  if (p.sunrise_tool_template.empty() != p.sunrise_tool_frame.empty()) {
    problems.push_back(where + (p.sunrise_tool_frame.empty() ? ".sunrise.tool_frame" : ".sunrise.tool_template") +
                       ": missing (tool_template and tool_frame go together: the template and "
                       "the cylinder's frame in it)");
  }
}

}  // namespace

RobotCell read_robot_cell(const nlohmann::json& j, const std::string& origin,
                          std::vector<std::string>& problems) {
  RobotCell c;
  const bool is_robot = j.at("kinematics").at("type") == "robot-holds-substrate";
  if (!is_robot) {
    if (j.contains("robot") || j.contains("extruder")) {
      problems.push_back(origin +
                         ": robot/extruder: only for kinematics.type = robot-holds-substrate");
    }
    return c;
  }
  if (!j.contains("robot") || !j.contains("extruder")) {
    problems.push_back(origin + ": robot/extruder: missing (required for robot-holds-substrate)");
    return c;
  }
  c.enabled = true;
  const auto& r = j.at("robot");
  const std::string where = origin + ": robot";
  c.arm = r.value("arm", c.arm);
  if (c.arm == "ur10e") {
    c.controller = RobotController::UniversalRobots;
    c.axes = 6;
    c.joint_limits_deg = {360, 360, 360, 360, 360, 360, 0};
  } else if (c.arm == "irb1200-5-0.9") {
    c.controller = RobotController::Abb;
    c.axes = 6;
    c.joint_limits_deg = {170, 130, 70, 270, 130, 400, 0};
    c.joint_min_deg = std::array<double, 7>{-170, -100, -200, -270, -130, -400, 0};
  }
  const std::size_t axes = static_cast<std::size_t>(c.axes);
  const std::string joint_names = axes == 7 ? "7 joints (A1..A7)" : "6 joints (J1..J6)";
  c.v_cart_mm_per_s = r.value("v_cart_mm_per_s", c.v_cart_mm_per_s);
  c.travel_speed_mm_per_s = r.value("travel_speed_mm_per_s", c.travel_speed_mm_per_s);
  c.lift_mm = r.value("lift_mm", c.lift_mm);
  if (r.contains("joint_limits_deg")) {
    const auto& l = r.at("joint_limits_deg");
    if (l.size() != axes) problems.push_back(where + ".joint_limits_deg: must list " + joint_names);
    for (std::size_t i = 0; i < axes && i < l.size(); ++i)
      c.joint_limits_deg[i] = l[i].get<double>();
  }
  if (r.contains("joint_min_deg")) {
    const auto& l = r.at("joint_min_deg");
    if (l.size() != axes) problems.push_back(where + ".joint_min_deg: must list " + joint_names);
    std::array<double, 7> lo{};
    for (std::size_t i = 0; i < axes && i < l.size(); ++i) lo[i] = l[i].get<double>();
    c.joint_min_deg = lo;
  }
  for (std::size_t i = 0; i < axes; ++i) {
    const double lo = c.joint_min_deg ? (*c.joint_min_deg)[i] : -c.joint_limits_deg[i];
    if (!(lo < c.joint_limits_deg[i])) {
      problems.push_back(where + ".joint_min_deg: joint " + std::to_string(i + 1) +
                         " must be below its upper limit in joint_limits_deg");
      break;
    }
  }
  c.joint_margin_deg = r.value("joint_limit_margin_deg", c.joint_margin_deg);
  c.reach_mm = r.value("reach_mm", c.reach_mm);
  c.nozzle_tip_mm = vec3_or(r, "nozzle_tip_mm", c.nozzle_tip_mm);
  c.nozzle_axis = direction(r, "nozzle_axis", c.nozzle_axis, where, problems);
  c.substrate_axis = direction(r, "substrate_axis", c.substrate_axis, where, problems);
  if (std::abs(c.nozzle_axis.dot(c.substrate_axis)) > 1e-6) {
    problems.push_back(where +
                       ".substrate_axis: must be perpendicular to nozzle_axis (the nozzle meets "
                       "the cylinder's side)");
  }
  c.mount_mm = r.value("mount_mm", c.mount_mm);
  c.mount_rotation_deg = r.value("mount_rotation_deg", c.mount_rotation_deg);
  if (r.contains("nozzle_cone")) {
    const auto& cone = r.at("nozzle_cone");
    c.nozzle_cone.half_angle_deg = cone.value("half_angle_deg", c.nozzle_cone.half_angle_deg);
    c.nozzle_cone.length_mm = cone.value("length_mm", c.nozzle_cone.length_mm);
    c.nozzle_cone.tip_radius_mm = cone.value("tip_radius_mm", c.nozzle_cone.tip_radius_mm);
  }
  if (r.contains("keep_out")) {
    const auto& body = r.at("keep_out");
    c.keep_out.radius_mm = body.value("radius_mm", c.keep_out.radius_mm);
    c.keep_out.length_mm = body.value("length_mm", c.keep_out.length_mm);
  }
  c.extruder = read_extruder(j.at("extruder"));
  c.programs = read_programs(r);
  c.motion = read_motion(r);
  if (c.motion.home_joints_deg) {
    if (r.at("home_joints_deg").size() != axes)
      problems.push_back(where + ".home_joints_deg: must list " + joint_names);
    for (std::size_t i = 0; i < axes; ++i) {
      const double q = (*c.motion.home_joints_deg)[i];
      const double lo = c.joint_min_deg ? (*c.joint_min_deg)[i] : -c.joint_limits_deg[i];
      if (q > c.joint_limits_deg[i] || q < lo) {
        problems.push_back(where + ".home_joints_deg: A" + std::to_string(i + 1) +
                           " is beyond its joint limit");
        break;
      }
    }
  }
  // Pasted into the Sunrise program as code (a type and method names): identifiers only.
  for (const auto& [key, value] : {std::pair{"io_group", c.programs.sunrise_io_group},
                                   std::pair{"lap_signal", c.programs.sunrise_lap_signal}}) {
    try {
      require_java_identifier(where + ".sunrise." + key, value);
    } catch (const InputError& e) {
      problems.push_back(e.what());
    }
  }
  if (!c.programs.sunrise_ready_signal.empty()) {
    try {
      require_java_identifier(where + ".sunrise.ready_signal", c.programs.sunrise_ready_signal);
    } catch (const InputError& e) {
      problems.push_back(e.what());
    }
  }
  // Pasted into the RAPID module as names of its data and signals: RAPID identifiers only.
  for (const auto& [key, value] :
       {std::pair{"tool", c.programs.rapid_tool}, std::pair{"wobj", c.programs.rapid_wobj},
        std::pair{"lap_signal", c.programs.rapid_lap_signal},
        std::pair{"ready_signal", c.programs.rapid_ready_signal}}) {
    if (std::string(key) == "ready_signal" && value.empty()) continue;
    try {
      require_rapid_identifier(where + ".rapid." + key, value);
    } catch (const InputError& e) {
      problems.push_back(e.what());
    }
  }
  if (c.programs.rapid_tool == c.programs.rapid_wobj)
    problems.push_back(where + ".rapid.wobj: must differ from rapid.tool");
  check_controller_data(r, c, where, problems);
  if (c.controller == RobotController::Abb && c.motion.path_acceleration_mm_per_s2 &&
      *c.motion.path_acceleration_mm_per_s2 < 100.0) {
    problems.push_back(where + ".acceleration_mm_per_s2 = " +
                       r.at("acceleration_mm_per_s2").dump() +
                       ": must be >= 100 on an ABB arm (PathAccLim takes at least 0.1 m/s^2)");
  }
  // A URScript movel commands its acceleration: one value for the program and the timing.
  if (c.controller == RobotController::UniversalRobots && c.motion.path_acceleration_mm_per_s2) {
    const auto u = r.value("urscript", nlohmann::json::object());
    if (!u.contains("acceleration_mm_per_s2")) {
      c.programs.ur_acceleration_mm_per_s2 = *c.motion.path_acceleration_mm_per_s2;
    } else if (c.programs.ur_acceleration_mm_per_s2 != *c.motion.path_acceleration_mm_per_s2) {
      problems.push_back(where +
                         ".acceleration_mm_per_s2: differs from robot.urscript.acceleration_mm_"
                         "per_s2 (the movel acceleration); give one of them");
    }
  }
  return c;
}

double corner_acceleration_mm_per_s2(const RobotCell& cell) {
  if (cell.motion.path_acceleration_mm_per_s2) return *cell.motion.path_acceleration_mm_per_s2;
  if (cell.controller == RobotController::UniversalRobots)
    return cell.programs.ur_acceleration_mm_per_s2;
  return kDefaultPathAccelerationMmPerS2;
}

RotaryAxis read_rotary_axis(const nlohmann::json& j, const std::string& origin,
                            std::vector<std::string>& problems) {
  RotaryAxis a;
  const bool is_rotary = j.at("kinematics").at("type") == "rotary";
  if (!is_rotary) {
    if (j.contains("rotary"))
      problems.push_back(origin + ": rotary: only for kinematics.type = rotary");
    return a;
  }
  if (!j.contains("rotary")) {
    problems.push_back(origin + ": rotary: missing (required for kinematics.type = rotary)");
    return a;
  }
  a.enabled = true;
  const auto& r = j.at("rotary");
  const std::string where = origin + ": rotary";
  a.letter = r.value("axis", std::string("A"))[0];
  a.axis_dir = direction(r, "axis_dir", a.axis_dir, where, problems);
  if (std::abs(a.axis_dir.z()) > 1e-6) {
    problems.push_back(
        where + ".axis_dir: must be horizontal (the nozzle points down onto the cylinder's side)");
  }
  a.axis_point_mm = vec3_or(r, "axis_point_mm", a.axis_point_mm);
  a.max_radius_mm = r.value("max_radius_mm", a.max_radius_mm);
  a.lift_mm = r.value("lift_mm", a.lift_mm);
  a.inverse_time = r.value("feed", std::string("xyz-distance")) == "inverse-time";
  const std::string flavour = j.at("firmware").at("flavour").get<std::string>();
  if (a.inverse_time && flavour != "reprap") {
    problems.push_back(where +
                       ".feed = \"inverse-time\": G93 needs firmware.flavour = reprap "
                       "(RepRapFirmware 3.5+); Marlin has no G93");
  }
  return a;
}

}  // namespace strand::machines
