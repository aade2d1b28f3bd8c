// Curved jobs: placement, pose planning, machine checks, writers and report.
#include "postprocess/plan/produce_curved.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "machines/extruder_gcode.h"
#include "machines/gcode_format.h"
#include "machines/joint_analysis.h"
#include "machines/kinematics.h"
#include "machines/krl_writer.h"
#include "machines/pose_csv.h"
#include "machines/program_text.h"
#include "machines/rapid_writer.h"
#include "machines/robot_transit.h"
#include "machines/rotary_gcode.h"
#include "machines/sunrise_writer.h"
#include "machines/urscript_writer.h"
#include "postprocess/plan/cylinder_placement.h"
#include "postprocess/plan/lap_timing.h"
#include "postprocess/plan/laps.h"
#include "postprocess/plan/planner.h"
#include "postprocess/plan/pose_planner.h"
#include "postprocess/plan/pose_report.h"
#include "postprocess/plan/produce_on_mesh.h"
#include "postprocess/plan/report.h"
#include "postprocess/plan/robot_transit_plan.h"
#include "slicer/input_error.h"
#include "slicer/mesh_io.h"
#include "slicer/params.h"
#include "slicer/units.h"

namespace strand::post {

using machines::MachineProfile;
using slicer::Feature;

namespace {

std::string deg(double rad) { return machines::fmt_fixed(slicer::rad_to_deg(rad), 1); }

// --extrusion time|volumetric: what drives the robot cell's extruder, over the profile's
// extruder.e_per_mm; a rotary printer's E is the bead volume already.
MachineProfile with_extrusion(const MachineProfile& profile, const slicer::SubstrateSpec& s) {
  MachineProfile m = profile;
  if (s.extrusion.empty()) return m;
  if (!m.robot.enabled) {
    throw InputError("substrate.extrusion = " + s.extrusion + ": only for a robot cell's extruder (" +
                     m.name + " is a rotary printer: its E is the bead volume)");
  }
  m.robot.extruder.time_based = s.extrusion == "time";
  return m;
}

void require_curved_machine(const MachineProfile& m) {
  if (m.robot.enabled || m.rotary.enabled) return;
  throw InputError("machine = " + m.name + " (" + machines::to_string(m.volume.kind) +
                   "): prints on a flat bed; substrate.type = cylinder needs a "
                   "robot-holds-substrate or rotary machine "
                   "(kuka-iiwa14-wasp-cylinder, marlin-rotary-a)");
}

// Contact speeds: a robot cell deposits at v_cart; a rotary printer at the job's speed and
// feature factors, capped like the planar planner (machine feed, volumetric flow).
PosePlanOptions plan_options(const slicer::Toolpath& t, const MachineProfile& m, double tol) {
  PosePlanOptions o;
  o.arc_tolerance_mm = tol;
  if (m.robot.enabled) {
    o.default_deposit_speed_mm_per_s = m.robot.v_cart_mm_per_s;
    o.travel_speed_mm_per_s = o.lift_speed_mm_per_s = m.robot.travel_speed_mm_per_s;
    o.lift_mm = m.robot.lift_mm;
    return o;
  }
  const PlanOptions planar = plan_options_from(t, tol);
  const double area = bead_areas_mm2(t).empty() ? 0.0 : bead_areas_mm2(t).front();
  for (Feature f : {Feature::Infill, Feature::Wall, Feature::Ligament, Feature::Node, Feature::Grip,
                    Feature::Frame, Feature::Link, Feature::Pen}) {
    double factor = 1.0;
    if (auto it = planar.speed_factors.find(f); it != planar.speed_factors.end()) {
      factor = it->second;
    } else if (auto pt = m.speed_factors.find(f); pt != m.speed_factors.end()) {
      factor = pt->second;
    }
    double v = slicer::mm_per_min_to_mm_per_s(
        std::min(planar.speed_mm_per_min * factor, m.limits.max_feed_mm_per_min));
    const double q_max = m.limits.max_volumetric_flow_mm3_per_s;
    if (m.deposition.model == machines::DepositionModel::EVolumetric && q_max > 0 && area > 0)
      v = std::min(v, q_max / area);
    o.deposit_speed_mm_per_s[f] = v;
  }
  o.travel_speed_mm_per_s = slicer::mm_per_min_to_mm_per_s(m.limits.travel_feed_mm_per_min);
  o.lift_speed_mm_per_s = slicer::mm_per_min_to_mm_per_s(m.limits.z_feed_mm_per_min);
  o.lift_mm = m.rotary.lift_mm;
  return o;
}

// The cylinder turns with the last joint: the whole program's turning must fit its window.
void check_turning(const slicer::PoseProgram& p, const MachineProfile& m) {
  const auto [lo, hi] = turn_range(p);
  const std::size_t last = static_cast<std::size_t>(m.robot.axes - 1);
  const double last_max = m.robot.joint_limits_deg[last];
  const double last_min = m.robot.joint_min_deg ? (*m.robot.joint_min_deg)[last] : -last_max;
  const double window = slicer::deg_to_rad(last_max - last_min - 2.0 * m.robot.joint_margin_deg);
  if (hi - lo <= window + 1e-9) return;
  std::size_t worst = 0;
  for (std::size_t k = 0; k < p.laps.size(); ++k) {
    const auto& l = p.laps[k];
    if (l.turn_max_rad - l.turn_min_rad > p.laps[worst].turn_max_rad - p.laps[worst].turn_min_rad)
      worst = k;
  }
  throw InputError(
      "substrate: the pattern turns the cylinder " + deg(hi - lo) + " deg (lap " +
      std::to_string(worst) + " of layer " + std::to_string(p.laps[worst].layer) + " alone " +
      deg(p.laps[worst].turn_max_rad - p.laps[worst].turn_min_rad) +
      " deg) and laps cannot split it further without breaking the strand; A" +
      std::to_string(last + 1) + " allows " + deg(window) + " deg (" +
      machines::fmt_fixed(last_min, 0) + ".." + machines::fmt_fixed(last_max, 0) + " less " +
      machines::fmt_fixed(m.robot.joint_margin_deg, 0) +
      " deg margin): use --wrap patch with a narrower pattern, a larger radius, or a rotary-axis "
      "machine");
}

nlohmann::json joints_json(const machines::JointReport& j, const machines::ArmModel& arm) {
  nlohmann::json joints = nlohmann::json::array();
  std::string text;
  for (int i = 0; i < j.axes; ++i) {
    const double lo = slicer::rad_to_deg(j.min_rad[i]), hi = slicer::rad_to_deg(j.max_rad[i]);
    joints.push_back({{"joint", "A" + std::to_string(i + 1)},
                      {"min_deg", std::round(lo * 100) / 100},
                      {"max_deg", std::round(hi * 100) / 100},
                      {"limit_deg", std::round(slicer::rad_to_deg(arm.limit_rad[i]) * 100) / 100}});
    text += (i ? ", " : "") + std::string("A") + std::to_string(i + 1) + " " +
            machines::fmt_fixed(lo, 0) + ".." + machines::fmt_fixed(hi, 0);
  }
  return {{"arm", arm.name},
          {"joints", joints},
          {"max_reach_mm", std::round(j.max_reach_mm * 10) / 10},
          {"reach_mm", arm.reach_mm},
          {"max_ik_error_mm", j.max_ik_error_mm},
          {"unreachable", j.unreachable},
          {"outside_limits", j.outside_limits},
          {"text", text + " deg; wrist " + machines::fmt_fixed(j.max_reach_mm, 0) + " of " +
                       machines::fmt_fixed(arm.reach_mm, 0) + " mm reach"}};
}

nlohmann::json check_robot(const slicer::PoseProgram& p, const MachineProfile& m) {
  check_turning(p, m);
  const machines::ArmModel arm = machines::arm_model(m.robot);
  const machines::JointReport j = machines::analyse_joints(arm, m.robot, p.points, false, 1);
  if (j.first_unreachable) {
    throw InputError("substrate: pose " + std::to_string(*j.first_unreachable) +
                     " is out of the robot's reach (" + j.first_unreachable_what +
                     "): move robot.nozzle_tip_mm or use a smaller cylinder");
  }
  if (j.first_outside) {
    throw InputError("substrate: pose " + std::to_string(*j.first_outside) + " needs " +
                     j.first_outside_what + " (" + std::to_string(j.outside_limits) +
                     " poses outside the joint limits)");
  }
  return joints_json(j, arm);
}

void check_rotary(const slicer::PoseProgram& p, const MachineProfile& m,
                  const slicer::SubstrateSpec& s) {
  const auto& r = m.rotary;
  if (s.radius_mm > r.max_radius_mm) {
    throw InputError("substrate.radius = " + slicer::short_number(s.radius_mm) +
                     ": must be <= " + slicer::short_number(r.max_radius_mm) + " on " + m.name +
                     " (the cylinder must clear the bed) (mm)");
  }
  const slicer::Vec3 far_end = r.axis_point_mm + s.length_mm * r.axis_dir;
  for (const slicer::Vec3& q : {far_end}) {
    if (auto why = machines::outside_reason(m.volume, q)) {
      throw InputError("substrate.length = " + slicer::short_number(s.length_mm) +
                       ": the cylinder's free end leaves " + m.name + "'s envelope (" + *why + ")");
    }
  }
  for (const auto& pt : p.points) {
    if (auto why = machines::outside_reason(m.volume, pt.tip_mm)) {
      throw InputError("substrate: the nozzle would leave " + m.name + "'s envelope (" + *why +
                       "): use a smaller radius or fewer layers");
    }
  }
}

}  // namespace

std::vector<std::string> curved_output_paths(const MachineProfile& m, const std::string& output) {
  const std::filesystem::path p(output);
  if (!m.robot.enabled) {
    const std::string ext = p.extension().string();
    if (ext != ".gcode" && ext != ".gco" && ext != ".g" && ext != ".nc") {
      throw InputError("output = " + output + ": " + m.name +
                       " writes rotary-axis G-code: give a .gcode (or .gco, .g, .nc) name");
    }
    return {output};
  }
  if (p.extension() != ".csv") {
    const char* beside =
        m.robot.controller == machines::RobotController::UniversalRobots ? ".script"
        : m.robot.controller == machines::RobotController::Abb           ? ".mod"
                                                                         : ".java, .src, .dat";
    throw InputError("output = " + output + ": " + m.name + " writes a pose CSV (and " + beside +
                     ", .extruder.gcode beside it): give a .csv name");
  }
  // Sunrise and KSS load a program only from the file named after its class or module:
  // those two are named after the sanitised stem, the CSV and the extruder's G-code keep it.
  const std::string base = output.substr(0, output.size() - 4);
  const std::string stem = p.stem().string();
  const std::filesystem::path dir = p.parent_path();
  if (m.robot.controller == machines::RobotController::UniversalRobots)
    return {output, base + ".script", base + ".extruder.gcode"};
  if (m.robot.controller == machines::RobotController::Abb)
    return {output, (dir / (machines::rapid_module_name(stem) + ".mod")).string(),
            base + ".extruder.gcode"};
  const std::string module = machines::krl_module_name(stem);
  return {output, (dir / (machines::java_class_name(stem) + ".java")).string(),
          (dir / (module + ".src")).string(), (dir / (module + ".dat")).string(),
          base + ".extruder.gcode"};
}

namespace {

std::vector<std::string> header_lines(const slicer::Toolpath& t, const slicer::SubstrateSpec& s,
                                      const MachineProfile& m, double tol) {
  std::vector<std::string> h;
  h.push_back("Strand " + t.generator + " on a cylinder (curved substrate)");
  h.push_back("machine: " + m.name + " (" + machines::to_string(m.volume.kind) + ")");
  h.push_back("substrate: cylinder radius " + slicer::short_number(s.radius_mm) + " mm, length " +
              slicer::short_number(s.length_mm) + " mm, wrap " + slicer::to_string(s.wrap) +
              ", arc length at " + slicer::to_string(s.arc_length_at));
  h.push_back("placement: " + placement_text(s));
  h.push_back("units: mm, s, deg");
  for (const auto& [k, v] : t.parameters.items())
    h.push_back("param " + k + " = " + slicer::value_text(v));
  h.push_back("param arc-tolerance = " + slicer::short_number(tol) +
              " (chord error on the surface)");
  for (const auto& [k, v] : t.derived.items()) {
    if (!v.is_string())
      h.push_back(
          "derived " + k + " = " +
          (v.is_number_float() ? machines::fmt_fixed(v.get<double>(), 4) : slicer::value_text(v)));
  }
  return h;
}

// The extruder's volume may differ from the beads' by this fraction before a warning.
constexpr double kVolumeBalanceTolerance = 0.10;

// The lap timing in the report: per lap the nominal and planned durations and the E pushed,
// and the whole in "lap_timing" (its text is the summary's line).
void add_lap_timing(nlohmann::json& report, const LapTiming& timing,
                    const machines::ExtruderProgram& extruder) {
  auto& laps = report["laps"];
  for (std::size_t k = 0; k < laps.size() && k < timing.planned_s.size(); ++k) {
    laps[k]["nominal_time_s"] = round_to(timing.nominal_s[k], 2);
    laps[k]["planned_time_s"] = round_to(timing.planned_s[k], 2);
    if (k < extruder.lap_e.size()) laps[k]["e"] = round_to(extruder.lap_e[k], 4);
  }
  report["lap_timing"] = lap_timing_json(timing);
}

// KUKA: Sunrise Java and KRL .src/.dat beside the CSV.
void write_kuka(CurvedProduced& out, const MachineProfile& m, const std::vector<std::string>& paths,
                const std::vector<std::string>& header, double tol, const std::string& csv,
                const std::string& ext, const machines::TransitPlan& transit) {
  const std::string base = std::filesystem::path(paths[0]).stem().string();
  const std::string java = machines::write_sunrise_java(
      out.program, m, base, std::filesystem::path(paths[0]).filename().string(), header,
      transit);
  const machines::KrlProgram krl = machines::write_krl(out.program, m, base, header, tol, transit);
  out.files = {
      {paths[0], csv}, {paths[1], java}, {paths[2], krl.src}, {paths[3], krl.dat}, {paths[4], ext}};
  const auto lines = [](const std::string& s) { return std::count(s.begin(), s.end(), '\n'); };
  out.report["outputs"] = {{"main", paths[0]},    {"csv", paths[0]},
                           {"java", paths[1]},    {"krl_src", paths[2]},
                           {"krl_dat", paths[3]}, {"extruder_gcode", paths[4]}};
  out.report["programs"] = {{"csv_rows", out.program.points.size()},
                            {"csv_bytes", csv.size()},
                            {"java_bytes", java.size()},
                            {"krl_src_bytes", krl.src.size()},
                            {"krl_dat_bytes", krl.dat.size()},
                            {"krl_sub_programs", krl.sub_programs},
                            {"krl_lin_points", krl.lin_points},
                            {"extruder_lines", lines(ext)},
                            {"extruder_bytes", ext.size()},
                            {"text", std::to_string(out.program.points.size()) + " CSV rows, KRL " +
                                         std::to_string(krl.sub_programs) + " sub-programs / " +
                                         std::to_string(krl.lin_points) + " LIN, extruder " +
                                         std::to_string(lines(ext)) + " lines"}};
}

// Robot cell: pose CSV, the controller's programs and the extruder's G-code.
void write_robot(CurvedProduced& out, const slicer::Toolpath& t, const MachineProfile& m,
                 const std::vector<std::string>& paths, const std::vector<std::string>& header,
                 double tol, const machines::TransitPlan& transit) {
  const std::string base = std::filesystem::path(paths[0]).stem().string();
  const std::string csv_name = std::filesystem::path(paths[0]).filename().string();
  const std::string csv = machines::write_pose_csv(out.program);
  // The extruder follows the laps as the robot runs them, corner slowdowns included.
  const LapTiming timing = time_laps(out.program, corner_model_for(m, tol));
  machines::ExtruderGcodeInfo xi{header, bead_areas_mm2(t), timing.t_s};
  const machines::ExtruderProgram extruder = machines::extruder_program(out.program, m, xi);
  const std::string& ext = extruder.gcode;
  const auto lines = [](const std::string& s) { return std::count(s.begin(), s.end(), '\n'); };
  const double e_total = extruder.e_total;
  add_lap_timing(out.report, timing, extruder);
  // Issue 37: each vendor program's contact speed against the time line (refused past 2 %).
  add_contact_speed(out.report, out.program, m);
  const auto controller = m.robot.controller;
  if (controller == machines::RobotController::UniversalRobots) {
    const std::string script = machines::write_urscript(
        out.program, m, machines::urscript_function_name(base), csv_name, header, tol, transit);
    out.files = {{paths[0], csv}, {paths[1], script}, {paths[2], ext}};
    out.report["outputs"] = {{"main", paths[0]},
                             {"csv", paths[0]},
                             {"urscript", paths[1]},
                             {"extruder_gcode", paths[2]}};
    out.report["programs"] = {
        {"csv_rows", out.program.points.size()},
        {"csv_bytes", csv.size()},
        {"urscript_bytes", script.size()},
        {"extruder_lines", lines(ext)},
        {"extruder_bytes", ext.size()},
        {"text", std::to_string(out.program.points.size()) + " CSV rows, URScript " +
                     std::to_string(lines(script)) + " lines, extruder " +
                     std::to_string(lines(ext)) + " lines"}};
  } else if (controller == machines::RobotController::Abb) {
    const std::string module = std::filesystem::path(paths[1]).stem().string();
    const machines::RapidProgram rapid =
        machines::write_rapid(out.program, m, module, csv_name, header, tol, transit);
    out.files = {{paths[0], csv}, {paths[1], rapid.mod}, {paths[2], ext}};
    out.report["outputs"] = {
        {"main", paths[0]}, {"csv", paths[0]}, {"rapid", paths[1]}, {"extruder_gcode", paths[2]}};
    out.report["programs"] = {
        {"csv_rows", out.program.points.size()},
        {"csv_bytes", csv.size()},
        {"rapid_bytes", rapid.mod.size()},
        {"rapid_procedures", rapid.procedures},
        {"rapid_move_l", rapid.move_l},
        {"extruder_lines", lines(ext)},
        {"extruder_bytes", ext.size()},
        {"text", std::to_string(out.program.points.size()) + " CSV rows, RAPID " +
                     std::to_string(rapid.procedures) + " procedures / " +
                     std::to_string(rapid.move_l) + " MoveL, extruder " +
                     std::to_string(lines(ext)) + " lines"}};
  } else {
    write_kuka(out, m, paths, header, tol, csv, ext, transit);
  }
  const double ink_ml = slicer::mm3_to_ml(e_total * m.deposition.mm3_per_e);
  const double bead_ml = out.report["totals"]["bead_volume_ml"].get<double>();
  const double ratio = bead_ml > 0.0 ? ink_ml / bead_ml : 1.0;
  out.report["ink"] = {
      {"e_total", std::round(e_total * 1e5) / 1e5},
      {"extruded_ml", std::round(ink_ml * 1e4) / 1e4},
      {"e_per_mm",
       m.robot.extruder.time_based ? "v_ext / v_cart (time-based)" : "bead area / mm3 per E"},
      {"extrusion", m.robot.extruder.time_based ? "time" : "volumetric"},
      {"text", "E " + machines::fmt_fixed(e_total, 2) + " (" + machines::fmt_fixed(ink_ml, 2) +
                   " mL from the extruder, beads " + machines::fmt_fixed(bead_ml, 2) + " mL)"},
      {"extruder_to_bead_ratio", std::round(ratio * 1e4) / 1e4}};
  // The extruder and the beads disagree past 10 %: the part will be starved or flooded.
  if (std::abs(ratio - 1.0) > kVolumeBalanceTolerance) {
    std::string fix = m.robot.extruder.time_based
                          ? "set extruder.v_ext_mm_per_min to " +
                                machines::fmt_fixed(m.robot.extruder.v_ext_mm_per_min / ratio, 1) +
                                ", calibrate deposition.mm3_per_e or use --extrusion volumetric"
                          : "calibrate deposition.mm3_per_e";
    out.report["warnings"].push_back("the extruder delivers " + machines::fmt_fixed(ratio, 2) +
                                     "x the beads' volume (" + machines::fmt_fixed(ink_ml, 2) +
                                     " vs " + machines::fmt_fixed(bead_ml, 2) + " mL): " + fix);
  }
}

void write_rotary(CurvedProduced& out, const slicer::Toolpath& t, const MachineProfile& m,
                  const std::vector<std::string>& paths, const std::vector<std::string>& header) {
  const std::string g =
      machines::write_rotary_gcode(out.program, m, {header, bead_areas_mm2(t), bead_widths_mm(t)});
  out.files = {{paths[0], g}};
  out.report["outputs"] = {{"main", paths[0]}, {"gcode", paths[0]}};
  const double ml = out.report["totals"]["bead_volume_ml"].get<double>();
  out.report["ink"] = {{"volume_ml", ml}, {"text", machines::fmt_fixed(ml, 2) + " mL"}};
  out.report["programs"] = {
      {"gcode_lines", std::count(g.begin(), g.end(), '\n')},
      {"gcode_bytes", g.size()},
      {"text", std::to_string(std::count(g.begin(), g.end(), '\n')) + " G-code lines"}};
}

// A robot-held mesh (produce_on_mesh.h): its own planner, the same checks and writers.
CurvedProduced produce_on_mesh(const slicer::Toolpath& t, const slicer::SubstrateSpec& s,
                               const MachineProfile& m, double tol, const std::string& output) {
  require_mesh_machine(m);
  const std::vector<std::string> paths = curved_output_paths(m, output);
  MeshJob job = plan_mesh_job(t, s, m, tol, output);
  CurvedProduced out;
  out.program = std::move(job.plan.program);
  nlohmann::json robot = check_robot(out.program, m);
  const machines::TransitPlan transit = plan_robot_transit(
      out.program, m,
      machines::mesh_workpiece(slicer::read_mesh_file(s.mesh_file()), printed_mm(out.program)), robot);
  out.report = std::move(job.report);
  out.report["parameters"]["arc-tolerance"] = tol;
  out.report["robot"] = robot;
  write_robot(out, job.placed, m, paths, job.header, tol, transit);
  out.files.push_back(job.record_file);
  out.report["outputs"]["substrate_record"] = job.record_file.first;
  out.summary = mesh_job_summary(out.report) + transit_summary(transit);
  out.summary += contact_speed_summary(out.report);  // issue 37
  return out;
}

}  // namespace

CurvedProduced produce_curved(const slicer::Toolpath& t, const slicer::SubstrateSpec& s,
                              const MachineProfile& profile, double tol,
                              const std::string& output) {
  if (s.type == "mesh") return produce_on_mesh(t, s, with_extrusion(profile, s), tol, output);
  require_curved_machine(profile);
  const MachineProfile m = with_extrusion(profile, s);
  const std::vector<std::string> paths = curved_output_paths(m, output);
  if (t.layers.empty()) throw InputError("the pattern has no layers to place on the cylinder");
  const slicer::CylinderSurface cylinder(slicer::cylinder_spec(s, t.layers.front().height_mm));
  const slicer::Toolpath placed = place_on_cylinder(t, s, cylinder);
  CurvedProduced out;
  out.program = plan_poses(placed, cylinder, machines::holder_of(m), plan_options(placed, m, tol));
  nlohmann::json robot;
  machines::TransitPlan transit;
  if (m.robot.enabled) {
    robot = check_robot(out.program, m);
    transit = plan_robot_transit(
        out.program, m,
        machines::cylinder_workpiece(s.radius_mm, s.length_mm, printed_mm(out.program)), robot);
  }
  if (m.rotary.enabled) check_rotary(out.program, m, s);
  out.report = pose_report(placed, s, m, out.program);
  out.report["parameters"]["arc-tolerance"] = tol;
  const std::vector<std::string> header = header_lines(placed, s, m, tol);
  if (m.robot.enabled) {
    out.report["robot"] = robot;
    write_robot(out, placed, m, paths, header, tol, transit);
  } else {
    write_rotary(out, placed, m, paths, header);
  }
  out.summary = pose_summary(out.report);
  if (m.robot.enabled) out.summary += transit_summary(transit);
  return out;
}

}  // namespace strand::post
