// Planning and checking a robot program's motions outside the laps (robot_transit.h).
#include "machines/robot_transit.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "machines/gcode_format.h"
#include "machines/joint_analysis.h"
#include "machines/transit_clearance.h"
#include "machines/workpiece_pose.h"
#include "slicer/mesh_collision.h"
#include "slicer/units.h"

namespace strand::machines {

namespace {

using transit::Clearance;

// Conservative advancement: a step may move workpiece points by the clearance the last sample
// proved above the margin, plus this much (so the walk always progresses): the clearance
// between samples is at least margin - kStepSlackMm.
constexpr double kStepSlackMm = 0.5;
// Near the nozzle (the final approach and the first retract), the exact cone test every this
// far along the motion.
constexpr double kNearStepMm = 0.1;
// Work bound per motion (a joint move across the whole range takes a few thousand).
constexpr std::size_t kMaxSamples = 200000;
// The clearance poses tried, as multiples of robot.clearance_mm.
constexpr double kClearanceFactors[] = {1.0, 1.5, 2.0, 3.0};

Eigen::Isometry3d pose_of(const slicer::PosePoint& p) {
  Eigen::Isometry3d w = Eigen::Isometry3d::Identity();
  w.translate(p.workpiece_origin_mm);
  w.rotate(rotation_of(p.workpiece_wxyz));
  return w;
}

// Walks s from 0 to 1 by conservative advancement: `pose(s)` the workpiece, `disp_per_s` a bound
// of how far any workpiece point moves per unit s.
template <class PoseAt>
TransitMotion walk(const std::string& name, bool joint, const Clearance& c, PoseAt pose,
                   double disp_per_s, double printed, double margin) {
  TransitMotion m;
  m.name = name;
  m.joint = joint;
  m.min_clearance_mm = std::numeric_limits<double>::infinity();
  double s = 0.0;
  while (true) {
    const double lb = c.lower_bound(pose(s), printed, true);
    ++m.samples;
    if (lb < m.min_clearance_mm) m.min_clearance_mm = lb, m.at_fraction = s;
    if (lb < margin || m.samples >= kMaxSamples) {
      m.collides = true;
      return m;
    }
    if (s >= 1.0) break;
    const double step_mm = lb - margin + kStepSlackMm;
    s = disp_per_s <= 0.0 ? 1.0 : std::min(1.0, s + step_mm / disp_per_s);
  }
  return m;
}

// The linear motions that end or start at the nozzle: a translation along the nozzle axis,
// the exact cone test every kNearStepMm, the keep-out's lower bound every sample.
TransitMotion near_leg(const std::string& name, const Clearance& c, const slicer::PosePoint& a,
                       const slicer::PosePoint& b) {
  TransitMotion m;
  m.name = name;
  m.near_nozzle = true;
  const Eigen::Isometry3d wa = pose_of(a), wb = pose_of(b);
  const double length = (b.workpiece_origin_mm - a.workpiece_origin_mm).norm();
  const int n = std::max(1, static_cast<int>(std::ceil(length / kNearStepMm)));
  m.min_clearance_mm = std::numeric_limits<double>::infinity();
  for (int k = 0; k <= n; ++k) {
    const double s = static_cast<double>(k) / n;
    Eigen::Isometry3d w = wa;
    w.translation() = (1.0 - s) * wa.translation() + s * wb.translation();
    ++m.samples;
    const double body = c.lower_bound(w, 0.0, false);
    if (body < m.min_clearance_mm) m.min_clearance_mm = body, m.at_fraction = s;
    if (body < 0.0 || c.cone_hits(w)) {
      m.collides = true;
      m.at_fraction = s;
      return m;
    }
  }
  return m;
}

TransitMotion joint_move(const std::string& name, const ArmModel& arm, const RobotCell& cell,
                         const Clearance& c, const Joints& q0, const Joints& q1, double printed,
                         double margin) {
  // Joint i turns the links after it, the workpiece's frame on the flange and the workpiece:
  // any workpiece point is within `outer` (those lengths summed) of joint i's axis, so over
  // the move it travels at most the sum of |dq_i| outer_i.
  const Eigen::Isometry3d wif = workpiece_in_flange(cell);
  const Joints dq = q1 - q0;
  double outer = wif.translation().norm() + c.bound_radius_mm() + 1.0 + arm.flange_mm;
  double disp_per_s = 0.0;
  for (int i = arm.axes - 1; i >= 0; --i) {
    outer += std::abs(arm.dh[i].a_mm) + std::abs(arm.dh[i].d_mm);
    disp_per_s += std::abs(dq[i]) * outer;
  }
  return walk(
      name, true, c, [&](double s) { return forward_kinematics(arm, q0 + s * dq) * wif; },
      disp_per_s, printed, margin);
}

TransitMotion linear_move(const std::string& name, const Clearance& c, const slicer::PosePoint& a,
                          const slicer::PosePoint& b, double printed, double margin) {
  const Eigen::Quaterniond qa(rotation_of(a.workpiece_wxyz)), qb(rotation_of(b.workpiece_wxyz));
  const double angle = qa.angularDistance(qb);
  const double disp =
      (b.workpiece_origin_mm - a.workpiece_origin_mm).norm() + angle * c.bound_radius_mm();
  return walk(
      name, false, c,
      [&](double s) {
        Eigen::Isometry3d w = Eigen::Isometry3d::Identity();
        w.translate((1.0 - s) * a.workpiece_origin_mm + s * b.workpiece_origin_mm);
        w.rotate(qa.slerp(s, qb));
        return w;
      },
      disp, printed, margin);
}

std::string mm(double v) { return fmt_fixed(v, 1) + " mm"; }

// "sweeps the workpiece 11.5 mm into the nozzle's cone or keep-out" / "to 2.1 mm of ...".
std::string how_close(const TransitMotion& m, double margin) {
  const std::string at = " at " + fmt_fixed(100.0 * m.at_fraction, 0) + " % of the move";
  if (m.near_nozzle) return "the substrate enters the nozzle's cone or keep-out" + at;
  if (m.min_clearance_mm < 0.0)
    return "sweeps the workpiece " + mm(-m.min_clearance_mm) +
           " into the nozzle's cone or keep-out" + at;
  return "brings the workpiece to " + mm(m.min_clearance_mm) +
         " of the nozzle's cone or keep-out" + at + " (robot.transit_margin_mm = " +
         fmt_fixed(margin, 1) + ")";
}

double rounded(double v) { return std::round(v * 100.0) / 100.0; }

}  // namespace

TransitWorkpiece cylinder_workpiece(double radius_mm, double length_mm, double printed_mm) {
  TransitWorkpiece wp;
  const int n = 96;
  // Circumscribed: the facets' midlines at the radius, so the mesh holds the whole cylinder.
  const double r = radius_mm / std::cos(M_PI / n);
  slicer::Mesh& m = wp.mesh;
  for (int end = 0; end < 2; ++end)
    for (int i = 0; i < n; ++i) {
      const double a = 2.0 * M_PI * i / n;
      m.vertices_mm.emplace_back(r * std::cos(a), r * std::sin(a), end * length_mm);
    }
  m.vertices_mm.emplace_back(0.0, 0.0, 0.0);
  m.vertices_mm.emplace_back(0.0, 0.0, length_mm);
  const int c0 = 2 * n, c1 = 2 * n + 1;
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    m.triangles.push_back({i, j, n + j});
    m.triangles.push_back({i, n + j, n + i});
    m.triangles.push_back({c0, j, i});
    m.triangles.push_back({c1, n + i, n + j});
  }
  wp.cylinder_radius_mm = radius_mm;
  wp.cylinder_length_mm = length_mm;
  wp.printed_mm = printed_mm;
  return wp;
}

TransitWorkpiece mesh_workpiece(slicer::Mesh mesh, double printed_mm) {
  TransitWorkpiece wp;
  wp.mesh = std::move(mesh);
  wp.printed_mm = printed_mm;
  return wp;
}

TransitPlan plan_transit(const RobotCell& cell, const slicer::PoseProgram& program,
                         const TransitWorkpiece& workpiece, const std::optional<Joints>& last) {
  return plan_transit(cell, program.points, workpiece, last);
}

TransitPlan plan_transit(const RobotCell& cell, const std::vector<slicer::PosePoint>& points,
                         const TransitWorkpiece& workpiece,
                         const std::optional<Joints>& last_joints) {
  TransitPlan plan;
  if (points.empty() || workpiece.mesh.triangles.empty()) {
    plan.ok = false;
    plan.problem = "robot: nothing to plan (no poses or no workpiece)";
    return plan;
  }
  const ArmModel arm = arm_model(cell);
  const RobotMotionSetup& mo = cell.motion;
  const double margin = mo.transit_margin_mm;
  const Clearance clearance(cell, workpiece);
  const auto fail = [&](std::string why) {
    if (plan.ok) plan.ok = false, plan.problem = std::move(why);
  };
  if (!mo.home_joints_deg) {
    fail("robot.home_joints_deg: not set: the program's first joint move would start wherever "
         "the arm stands, and its sweep could not be checked against the nozzle (give the "
         "cell's home posture)");
    return plan;
  }
  Joints home = Joints::Zero();
  for (int i = 0; i < arm.axes; ++i) home[i] = slicer::deg_to_rad((*mo.home_joints_deg)[i]);
  plan.home = home;
  const slicer::PosePoint& first = points.front();
  const slicer::PosePoint& last = points.back();

  // Start: the near leg does not depend on the clearance pose.
  plan.start_approach = moved_along_nozzle(cell, first, mo.approach_mm);
  const TransitMotion approach_leg =
      near_leg("approach -> first pose", clearance, plan.start_approach, first);
  std::vector<TransitMotion> start;
  std::string start_problem;
  for (double factor : kClearanceFactors) {
    const double d = std::max(mo.clearance_mm * factor, mo.approach_mm);
    const slicer::PosePoint cp = moved_along_nozzle(cell, first, d);
    const JointReport jr = analyse_joints(arm, cell, {cp}, true);
    if (!jr.ok() || jr.solutions.empty()) {
      if (start_problem.empty())
        start_problem = "the clearance pose " + mm(d) + " from the first pose is out of the arm's "
                        "range (" + (jr.first_unreachable ? jr.first_unreachable_what
                                                          : jr.first_outside_what) + ")";
      continue;
    }
    std::vector<TransitMotion> ms;
    ms.push_back(joint_move("home -> clearance pose", arm, cell, clearance, home,
                            jr.solutions.front(), 0.0, margin));
    if (d > mo.approach_mm)
      ms.push_back(linear_move("clearance pose -> approach", clearance, cp, plan.start_approach,
                               0.0, margin));
    const auto bad = std::find_if(ms.begin(), ms.end(), [](const auto& m) { return m.collides; });
    if (bad == ms.end()) {
      plan.start_clearance = cp;
      plan.start_clearance_joints = jr.solutions.front();
      plan.start_clearance_mm = d;
      start = std::move(ms);
      break;
    }
    if (start_problem.empty() || factor == kClearanceFactors[0])
      start_problem = "the " + bad->name + " move (clearance pose " + mm(d) + " from the first "
                      "pose) " + how_close(*bad, margin);
  }
  if (start.empty()) {
    fail("robot.home_joints_deg: the start cannot be planned clear of the nozzle: " +
         start_problem + "; clearance poses of 1, 1.5, 2 and 3 x robot.clearance_mm tried "
         "(teach a home posture farther from the nozzle)");
  }
  if (approach_leg.collides) {
    fail("robot.approach_mm: on the approach onto the first pose " +
         how_close(approach_leg, margin));
  }
  for (auto& m : start) plan.motions.push_back(std::move(m));
  plan.motions.push_back(approach_leg);

  // End: retract, clearance pose, home; printed layers on the workpiece.
  const double printed = workpiece.printed_mm;
  plan.end_retract = moved_along_nozzle(cell, last, mo.retract_mm);
  const TransitMotion retract_leg = near_leg("last pose -> retract", clearance, last,
                                             plan.end_retract);
  if (retract_leg.collides)
    fail("robot.retract_mm: on the retract from the last pose " + how_close(retract_leg, margin));
  plan.motions.push_back(retract_leg);
  Joints q_last = Joints::Zero();
  if (last_joints) {
    q_last = *last_joints;
  } else {
    const JointReport all = analyse_joints(arm, cell, points, true, 1);
    if (!all.solutions.empty()) q_last = all.solutions.back();
  }
  std::vector<TransitMotion> end;
  std::string end_problem;
  for (double factor : kClearanceFactors) {
    const double d = std::max(mo.clearance_mm * factor, mo.retract_mm);
    const slicer::PosePoint cp = moved_along_nozzle(cell, last, d);
    const IkResult ik =
        solve_ik(arm, flange_pose(cell, cp.workpiece_origin_mm, cp.workpiece_wxyz), q_last, 400);
    if (!ik.converged || ik.position_error_mm > 0.01 || !within_limits(arm, ik.q)) {
      if (end_problem.empty())
        end_problem = "the clearance pose " + mm(d) + " from the last pose is out of the arm's "
                      "range";
      continue;
    }
    std::vector<TransitMotion> ms;
    if (d > mo.retract_mm)
      ms.push_back(linear_move("retract -> clearance pose", clearance, plan.end_retract, cp,
                               printed, margin));
    ms.push_back(
        joint_move("clearance pose -> home", arm, cell, clearance, ik.q, home, printed, margin));
    const auto bad = std::find_if(ms.begin(), ms.end(), [](const auto& m) { return m.collides; });
    if (bad == ms.end()) {
      plan.end_clearance = cp;
      plan.end_clearance_joints = ik.q;
      plan.end_clearance_mm = d;
      end = std::move(ms);
      break;
    }
    if (end_problem.empty() || factor == kClearanceFactors[0])
      end_problem = "the " + bad->name + " move (clearance pose " + mm(d) + " from the last "
                    "pose) " + how_close(*bad, margin);
  }
  if (end.empty()) {
    fail("robot.home_joints_deg: the end cannot be planned clear of the nozzle: " + end_problem +
         "; clearance poses of 1, 1.5, 2 and 3 x robot.clearance_mm tried (teach a home posture "
         "farther from the nozzle)");
  }
  for (auto& m : end) plan.motions.push_back(std::move(m));

  plan.min_clearance_mm = std::numeric_limits<double>::infinity();
  for (const auto& m : plan.motions) {
    if (m.near_nozzle || m.samples == 0) continue;
    if (m.min_clearance_mm < plan.min_clearance_mm)
      plan.min_clearance_mm = m.min_clearance_mm, plan.min_clearance_where = m.name;
  }
  if (!std::isfinite(plan.min_clearance_mm)) plan.min_clearance_mm = 0.0;
  return plan;
}

nlohmann::json transit_json(const TransitPlan& p) {
  nlohmann::json motions = nlohmann::json::array();
  for (const auto& m : p.motions) {
    motions.push_back({{"motion", m.name},
                       {"interpolation", m.joint ? "joint" : "linear"},
                       {"near_nozzle", m.near_nozzle},
                       {"min_clearance_mm", rounded(m.min_clearance_mm)},
                       {"at_fraction", rounded(m.at_fraction)},
                       {"samples", m.samples},
                       {"collides", m.collides}});
  }
  nlohmann::json j = {{"ok", p.ok},
                      {"start_clearance_mm", rounded(p.start_clearance_mm)},
                      {"end_clearance_mm", rounded(p.end_clearance_mm)},
                      {"min_clearance_mm", rounded(p.min_clearance_mm)},
                      {"min_clearance_motion", p.min_clearance_where},
                      {"motions", motions}};
  if (!p.ok) j["problem"] = p.problem;
  return j;
}

std::string transit_text(const TransitPlan& p) {
  if (!p.ok) return "COLLIDES: " + p.problem;
  return "smallest clearance " + mm(p.min_clearance_mm) + " (" + p.min_clearance_where +
         "), clearance poses " + fmt_fixed(p.start_clearance_mm, 0) + " / " +
         fmt_fixed(p.end_clearance_mm, 0) + " mm, " + std::to_string(p.motions.size()) +
         " motions checked";
}

}  // namespace strand::machines
