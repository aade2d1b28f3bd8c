// Reading the plotter and pen blocks of a machine profile.
#include "machines/plotter_profile.h"

namespace strand::machines {

namespace {

slicer::Vec2 vec2_or(const nlohmann::json& j, const char* key, const slicer::Vec2& fallback) {
  if (!j.contains(key)) return fallback;
  return slicer::Vec2(j.at(key)[0].get<double>(), j.at(key)[1].get<double>());
}

PenSetup read_pen(const nlohmann::json& p) {
  PenSetup s;
  const std::string lift = p.value("lift", std::string("servo"));
  s.lift = lift == "z" ? PenLift::Z : lift == "drum" ? PenLift::Drum : PenLift::Servo;
  s.count = p.value("count", s.count);
  s.width_mm = p.value("width_mm", s.width_mm);
  s.capacity_mm = p.value("capacity_mm", s.capacity_mm);
  s.pause_on_empty = p.value("pause_on_empty", s.pause_on_empty);
  if (p.contains("change_gcode")) s.change_gcode = p.at("change_gcode").get<std::vector<std::string>>();
  s.servo_index = p.value("servo_index", s.servo_index);
  s.up_value = p.value("up_value", s.up_value);
  s.down_value = p.value("down_value", s.down_value);
  s.dwell_s = p.value("dwell_s", s.dwell_s);
  s.z_up_mm = p.value("z_up_mm", s.z_up_mm);
  s.z_down_mm = p.value("z_down_mm", s.z_down_mm);
  s.draw_feed_mm_per_min = p.value("draw_feed_mm_per_min", s.draw_feed_mm_per_min);
  if (p.contains("drum")) {
    const auto& d = p.at("drum");
    s.drum.engage_step_deg = d.value("engage_step_deg", s.drum.engage_step_deg);
    s.drum.rest_offset_deg = d.value("rest_offset_deg", s.drum.rest_offset_deg);
    s.drum.write_offset_deg = d.value("write_offset_deg", s.drum.write_offset_deg);
  }
  if (p.contains("erase")) {
    const auto& e = p.at("erase");
    s.erase.disc_diameter_mm = e.value("disc_diameter_mm", 0.0);
    s.erase.offset_mm = vec2_or(e, "offset_mm", s.erase.offset_mm);
    s.erase.temperature_c = e.value("temperature_c", 0.0);
    s.erase.dwell_s = e.value("dwell_s", 0.0);
    s.erase.feed_mm_per_min = e.value("feed_mm_per_min", s.erase.feed_mm_per_min);
  }
  return s;
}

}  // namespace

std::string to_string(PlotterKind k) {
  switch (k) {
    case PlotterKind::Xy: return "xy";
    case PlotterKind::Polargraph: return "polargraph";
    case PlotterKind::PolarRTheta: return "polar-rtheta";
  }
  return "";
}

Plotter read_plotter(const nlohmann::json& j, const std::string& origin,
                     std::vector<std::string>& problems) {
  Plotter out;
  if (!j.contains("plotter")) return out;
  out.enabled = true;
  const auto& p = j.at("plotter");
  PlotterSetup& s = out.setup;
  const std::string kind = p.value("kinematics", std::string("xy"));
  s.kind = kind == "polargraph" ? PlotterKind::Polargraph
           : kind == "polar-rtheta" ? PlotterKind::PolarRTheta : PlotterKind::Xy;
  s.motor_distance_mm = p.value("motor_distance_mm", 0.0);
  s.gondola_width_mm = p.value("gondola_width_mm", 0.0);
  s.pen_offset_mm = p.value("pen_offset_mm", 0.0);
  s.min_tension = p.value("min_tension", s.min_tension);
  s.max_tension = p.value("max_tension", s.max_tension);
  s.max_resolution_loss = p.value("max_resolution_loss", s.max_resolution_loss);
  s.home_mm = vec2_or(p, "home_mm", s.home_mm);
  s.pivot_mm = vec2_or(p, "pivot_mm", s.pivot_mm);
  s.lever_mm = p.value("lever_mm", 0.0);
  s.origin_radius_mm = p.value("origin_radius_mm", 0.0);
  s.steps_per_mm = vec2_or(p, "steps_per_mm", s.steps_per_mm);
  if (s.kind == PlotterKind::Polargraph && s.motor_distance_mm <= s.gondola_width_mm) {
    problems.push_back(origin + ": plotter.motor_distance_mm: must exceed gondola_width_mm (required for polargraph)");
  }
  if (s.kind == PlotterKind::PolarRTheta && (s.lever_mm <= 0 || s.origin_radius_mm <= 0)) {
    problems.push_back(origin + ": plotter.lever_mm/origin_radius_mm: must be > 0 (required for polar-rtheta)");
  }
  if (s.min_tension >= s.max_tension) {
    problems.push_back(origin + ": plotter.min_tension: must be below max_tension");
  }
  out.pen = read_pen(j.value("pen", nlohmann::json::object()));
  const auto& k = j.at("kinematics");
  if (k.contains("min_mm") && k.contains("max_mm")) {
    out.area_min_mm = slicer::Vec2(k.at("min_mm")[0].get<double>(), k.at("min_mm")[1].get<double>());
    out.area_max_mm = slicer::Vec2(k.at("max_mm")[0].get<double>(), k.at("max_mm")[1].get<double>());
  }
  return out;
}

}  // namespace strand::machines
