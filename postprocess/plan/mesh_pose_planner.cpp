// Mesh pose planning: the path's targets (mesh_path_targets.cpp) given orientations by the
// smallest tilt from the reference pose and a rotation about the nozzle axis per pass,
// tracked by inverse kinematics, passes restarted turned where the arm's range ends.
#include "postprocess/plan/mesh_pose_planner.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <optional>
#include <set>
#include <string>

#include "machines/gcode_format.h"
#include "machines/joint_analysis.h"
#include "machines/robot_arm.h"
#include "machines/workpiece_pose.h"
#include "postprocess/plan/mesh_path_targets.h"
#include "slicer/input_error.h"
#include "slicer/mesh_row_rule.h"
#include "slicer/params.h"
#include "slicer/units.h"

namespace strand::post {

using machines::Joints;
using mesh_detail::PathBuilder;
using mesh_detail::Target;
using mesh_detail::where;
using slicer::PosePoint;
using slicer::Vec3;

namespace {

// Largest turn about the nozzle axis between two poses of a restart, deg.
constexpr double kTurnStepDeg = 1.0;
// Largest joint move between neighbouring poses, deg: more means a posture near a singular
// one (a wrist flipping over); such a pose ends the pass as a joint limit does.
constexpr double kMaxJointStepDeg = 10.0;
// Points simulated ahead when choosing a rotation.
constexpr std::size_t kLookahead = 300;
// A solution counts when its flange is this close to the target (as joint_analysis), mm, rad.
constexpr double kSolvedMm = 1e-3;
constexpr double kSolvedRad = 1e-6;

// The smallest rotation taking the workpiece normal `n` (workpiece frame) from where `r`
// puts it onto `up`, applied after r.
Eigen::Matrix3d tilted(const Eigen::Matrix3d& r, const Vec3& n, const Vec3& up) {
  const Eigen::Matrix3d out = Eigen::Quaterniond::FromTwoVectors(r * n, up).toRotationMatrix() * r;
  return machines::rotation_of(machines::quaternion_wxyz(out));  // re-orthonormalised
}

Eigen::Matrix3d about(const Vec3& up, double rad) {
  return Eigen::AngleAxisd(rad, up).toRotationMatrix();
}

// Where the arm stands: the pass's rotation about the nozzle axis, the last pose's joints and
// quaternion (its sign carried on for continuity).
struct ArmState {
  double psi = 0.0;
  Joints q = Joints::Zero();
  slicer::Quat4 wxyz = slicer::Quat4(1, 0, 0, 0);
};

class Poser {
 public:
  Poser(const slicer::MeshSubstrate& s, const machines::RobotCell& cell, PathBuilder& path)
      : s_(s),
        cell_(cell),
        path_(path),
        arm_(machines::arm_model(cell)),
        up_(-cell.nozzle_axis.normalized()),
        reference_(mesh_reference_rotation(s.facing(), cell)) {}

  MeshPlan run(const std::vector<Target>& targets) {
    targets_ = &targets;
    start(targets.front());
    for (std::size_t i = 1; i < targets.size(); ++i) {
      std::string why;
      std::optional<Posed> next = step(state_, targets[i], &why);
      if (!next) {
        restart(i, why);
        next = step(state_, targets[i], &why);
        if (!next) throw std::logic_error("mesh pose planner: a restart did not present its point");
      }
      emit(*next, targets[i]);
    }
    finish();
    return std::move(plan_);
  }

 private:
  using Posed = std::pair<PosePoint, ArmState>;

  // The orientation rule: the smallest rotation from the reference pose that turns the normal
  // against the nozzle (a function of the normal alone: no twist gathers along loops of the
  // path), then the pass's rotation `psi` about the nozzle axis.
  Eigen::Matrix3d orientation(const Vec3& n, double psi) const {
    return about(up_, psi) * tilted(reference_, n, up_);
  }

  // The pose for `t` with orientation r, continuing a program whose last quaternion is prev.
  PosePoint pose(const Target& t, const Eigen::Matrix3d& r, const slicer::Quat4* prev) const {
    PosePoint p;
    p.contact_mm = t.frame.point_mm;
    p.normal = t.frame.normal;
    p.workpiece_wxyz = machines::quaternion_wxyz(r);
    if (prev && p.workpiece_wxyz.dot(*prev) < 0) p.workpiece_wxyz = -p.workpiece_wxyz;
    p.tip_mm = cell_.nozzle_tip_mm;
    p.workpiece_origin_mm = cell_.nozzle_tip_mm - r * t.frame.point_mm;
    p.uv_mm = t.uv;
    p.offset_mm = t.offset;
    p.turn_rad = 0.0;
    p.extrude = t.extrude;
    p.layer = t.layer;
    p.feature = t.feature;
    return p;
  }

  // Joints for p from `seed` (or, without one, as analyse_joints solves a first pose), within
  // the limits less the margin and the reach; nullopt with the reason otherwise.
  std::optional<Joints> solve(const PosePoint& p, const Joints* seed, std::string* why,
                              bool bound_step = true) const {
    const Eigen::Isometry3d target =
        machines::flange_pose(cell_, p.workpiece_origin_mm, p.workpiece_wxyz);
    const double reach = (machines::wrist_centre(arm_, target) - arm_.shoulder_mm).norm();
    if (reach > arm_.reach_mm - kMeshReachMarginMm) {
      if (why)
        *why = "the wrist would be " + machines::fmt_fixed(reach, 1) +
               " mm from the shoulder, beyond the reach of " +
               machines::fmt_fixed(arm_.reach_mm, 0) + " mm";
      return std::nullopt;
    }
    Joints q;
    if (seed) {
      const machines::IkResult r = machines::solve_ik(arm_, target, *seed);
      if (!(r.position_error_mm < kSolvedMm && r.orientation_error_rad < kSolvedRad)) {
        if (why)
          *why = "no joint solution near the previous pose (position error " +
                 machines::fmt_fixed(r.position_error_mm, 3) + " mm)";
        return std::nullopt;
      }
      q = r.q;
      const Joints step = (q - *seed).cwiseAbs();
      int worst = 0;
      for (int i = 1; i < arm_.axes; ++i) worst = step[i] > step[worst] ? i : worst;
      if (bound_step && step[worst] > slicer::deg_to_rad(kMaxJointStepDeg)) {
        if (why)
          *why = "A" + std::to_string(worst + 1) + " would turn " +
                 machines::fmt_fixed(slicer::rad_to_deg(step[worst]), 1) +
                 " deg from the previous pose (near a singular posture; at most " +
                 machines::fmt_fixed(kMaxJointStepDeg, 0) + " deg)";
        return std::nullopt;
      }
    } else {
      const machines::JointReport j = machines::analyse_joints(arm_, cell_, {p}, true);
      if (!j.ok() || j.solutions.empty()) {
        if (why)
          *why = j.first_unreachable ? j.first_unreachable_what
                 : j.first_outside   ? "it needs " + j.first_outside_what
                                     : "no joint solution";
        return std::nullopt;
      }
      q = j.solutions.front();
    }
    const double margin = slicer::deg_to_rad(kMeshJointMarginDeg);
    for (int i = 0; i < arm_.axes; ++i) {
      if (q[i] > arm_.limit_rad[i] - margin || q[i] < arm_.limit_min_rad[i] + margin) {
        if (why) {
          const bool sym = arm_.limit_min_rad[i] == -arm_.limit_rad[i];
          *why = "it needs A" + std::to_string(i + 1) + " = " +
                 machines::fmt_fixed(slicer::rad_to_deg(q[i]), 1) + " deg, limit " +
                 (sym ? "+-" + machines::fmt_fixed(slicer::rad_to_deg(arm_.limit_rad[i]), 0)
                      : machines::fmt_fixed(slicer::rad_to_deg(arm_.limit_min_rad[i]), 0) + ".." +
                            machines::fmt_fixed(slicer::rad_to_deg(arm_.limit_rad[i]), 0)) +
                 " deg (less " + machines::fmt_fixed(kMeshJointMarginDeg, 1) + " deg margin)";
        }
        return std::nullopt;
      }
    }
    return q;
  }

  // The pose of `t` at rotation `psi`, solved from `st`'s joints.
  // A turn in place (`spinning`) may move the joints fast near a singular posture: it is slow
  // and continuous (1 deg steps), so only moves along the path are held to kMaxJointStepDeg.
  std::optional<Posed> posed(const ArmState& st, const Target& t, double psi, std::string* why,
                             bool spinning = false) const {
    const PosePoint p = pose(t, orientation(t.frame.normal, psi), &st.wxyz);
    const auto q = solve(p, &st.q, why, !spinning);
    if (!q) return std::nullopt;
    return Posed{p, ArmState{psi, *q, p.workpiece_wxyz}};
  }

  // The next pose of the pass.
  std::optional<Posed> step(const ArmState& st, const Target& t, std::string* why) const {
    return posed(st, t, st.psi, why);
  }

  // Points from index `from` presented in a row from `st` (at most kLookahead).
  std::size_t run_length(ArmState st, std::size_t from) const {
    const auto& ts = *targets_;
    std::size_t n = 0;
    for (std::size_t i = from; i < ts.size() && n < kLookahead; ++i, ++n) {
      const auto next = step(st, ts[i], nullptr);
      if (!next) break;
      st = next->second;
    }
    return n;
  }

  double mid_range_cost(const Joints& q) const {
    const Joints mid = (arm_.limit_rad + arm_.limit_min_rad) / 2.0;
    const Joints half = (arm_.limit_rad - arm_.limit_min_rad) / 2.0;
    double cost = 0.0;
    for (int i = 0; i < arm_.axes; ++i) cost += std::pow((q[i] - mid[i]) / half[i], 2);
    return cost;
  }

  // Rotations about the nozzle axis in the order they are tried: 0, +15, -15, +30, ... 180.
  static std::vector<double> candidates(bool with_zero) {
    std::vector<double> out;
    if (with_zero) out.push_back(0.0);
    const int n = static_cast<int>(std::lround(180.0 / kMeshRotationStepDeg));
    for (int k = 1; k <= n; ++k) {
      out.push_back(k * kMeshRotationStepDeg);
      if (k < n) out.push_back(-k * kMeshRotationStepDeg);
    }
    return out;
  }

  void start(const Target& first) {
    std::optional<Posed> best;
    std::size_t best_run = 0;
    double best_cost = 0.0;
    std::string why_zero;
    for (double deg : candidates(true)) {
      const double psi = slicer::deg_to_rad(deg);
      const PosePoint p = pose(first, orientation(first.frame.normal, psi), nullptr);
      std::string why;
      const auto q = solve(p, nullptr, &why);
      if (deg == 0.0) why_zero = why;
      if (!q) continue;
      const Posed here{p, ArmState{psi, *q, p.workpiece_wxyz}};
      const std::size_t n = 1 + run_length(here.second, 1);
      const double cost = mid_range_cost(*q);
      if (!best || n > best_run || (n == best_run && cost < best_cost - 1e-9))
        best = here, best_run = n, best_cost = cost;
    }
    if (!best) refuse(first, why_zero);
    plan_.first_rotation_deg = slicer::rad_to_deg(best->second.psi);
    emit(*best, first);
  }

  [[noreturn]] void refuse(const Target& t, const std::string& why) const {
    throw InputError(
        "substrate.mesh = " + s_.source() + ": the robot cannot present " + where(t) + ": " + why +
        " (at every rotation about the nozzle axis, " + slicer::short_number(kMeshRotationStepDeg) +
        " deg apart); move robot.nozzle_tip_mm or the mesh in its file (its "
        "coordinates are the workpiece frame on the flange), or use a smaller pattern");
  }

  // Simulates (or, with `emit_rows`, emits) a restart turned by `deg` about the nozzle axis:
  // backed off along the normal (unless the last pose already is), turned in steps of at most
  // kTurnStepDeg, and back at the last point. The state after it, or nullopt.
  std::optional<ArmState> turn(const Target& last, double deg, bool emit_rows) {
    ArmState st = state_;
    std::vector<std::pair<PosePoint, Target>> rows;
    const bool back_off = !last.lifted;
    const Target at = back_off ? path_.lifted(last, cell_.lift_mm) : last;
    if (back_off) {
      const auto next = step(st, at, nullptr);
      if (!next) return std::nullopt;
      rows.emplace_back(next->first, at);
      st = next->second;
    }
    const int n = std::max(1, static_cast<int>(std::ceil(std::abs(deg) / kTurnStepDeg)));
    const double psi0 = st.psi;
    Target spin = at;
    spin.extrude = false;
    spin.speed = cell_.travel_speed_mm_per_s;
    for (int k = 1; k <= n; ++k) {
      const auto next = posed(st, spin, psi0 + slicer::deg_to_rad(deg) * k / n, nullptr, true);
      if (!next) return std::nullopt;
      rows.emplace_back(next->first, spin);
      st = next->second;
    }
    if (back_off) {
      Target down = last;
      down.extrude = false;
      down.speed = at.speed;
      const auto next = step(st, down, nullptr);
      if (!next) return std::nullopt;
      rows.emplace_back(next->first, down);
      st = next->second;
    }
    if (emit_rows)
      for (const auto& [p, t] : rows) emit_pose(p, t);
    return st;
  }

  // Target i cannot follow the last pose: end the pass there, turn, start a new one.
  void restart(std::size_t i, const std::string& why) {
    const auto& ts = *targets_;
    const Target last = last_target_;
    std::optional<double> best_deg;
    std::size_t best_run = 0;
    for (double deg : candidates(false)) {
      const auto st = turn(last, deg, false);
      if (!st) continue;
      const std::size_t n = run_length(*st, i);
      if (n > best_run) best_run = n, best_deg = deg;
      if (n >= kLookahead || i + n >= ts.size()) break;  // the smallest turn that goes on
    }
    if (!best_deg || best_run == 0) refuse(ts[i], why);
    state_ = *turn(last, *best_deg, true);
    splits_.insert(plan_.program.points.size() - 1);
    ++plan_.restarts;
  }

  void emit_pose(const PosePoint& given, const Target& t) {
    PosePoint p = given;
    auto& pts = plan_.program.points;
    if (!pts.empty()) {
      const PosePoint& prev = pts.back();
      p.speed_mm_per_s = t.speed;
      p.t_s = prev.t_s + (p.contact_mm - prev.contact_mm).norm() / t.speed;
    }
    if (pts.size() >= kMaxPosePoints) {
      throw InputError("substrate.mesh = " + s_.source() + ": the program would need more than " +
                       std::to_string(kMaxPosePoints) +
                       " poses; raise arc-tolerance (mm) or print fewer layers");
    }
    pts.push_back(p);
    last_target_ = t;
  }

  void emit(const Posed& next, const Target& t) {
    emit_pose(next.first, t);
    state_ = next.second;
  }

  void finish() {
    auto& program = plan_.program;
    auto& pts = program.points;
    // Laps: a new one at every layer (owning its first point) and after every restart (sharing
    // the restart's last point with the pass before, as laps on a cylinder share their turn).
    std::vector<std::pair<std::size_t, std::size_t>> spans;
    std::size_t first = 0;
    for (std::size_t i = 1; i < pts.size(); ++i) {
      if (pts[i].layer != pts[i - 1].layer) {
        spans.emplace_back(first, i - 1);
        first = i;
      } else if (splits_.count(i - 1) && i - 1 > first) {
        spans.emplace_back(first, i - 1);
        first = i - 1;
      }
    }
    if (!pts.empty()) spans.emplace_back(first, pts.size() - 1);
    for (const auto& [a, b] : spans) {
      const int index = static_cast<int>(program.laps.size());
      const bool shares = a > 0 && pts[a].layer == pts[a - 1].layer;
      for (std::size_t k = shares ? a + 1 : a; k <= b; ++k) pts[k].lap = index;
      program.laps.push_back({pts[a].layer, 1, a, b, 0.0, 0.0});
    }
    bool first_rotation = true;
    for (const auto& p : pts) {
      const double deg = slicer::rad_to_deg(
          rotation_about(machines::rotation_of(p.workpiece_wxyz), reference_, up_));
      plan_.rotation_min_deg = first_rotation ? deg : std::min(plan_.rotation_min_deg, deg);
      plan_.rotation_max_deg = first_rotation ? deg : std::max(plan_.rotation_max_deg, deg);
      first_rotation = false;
      const double tilt = std::acos(std::clamp(p.normal.dot(s_.facing()), -1.0, 1.0));
      plan_.max_tilt_deg = std::max(plan_.max_tilt_deg, slicer::rad_to_deg(tilt));
    }
  }

  const slicer::MeshSubstrate& s_;
  const machines::RobotCell& cell_;
  PathBuilder& path_;
  machines::ArmModel arm_;
  Vec3 up_;
  Eigen::Matrix3d reference_;
  const std::vector<Target>* targets_ = nullptr;
  ArmState state_;
  Target last_target_;
  std::set<std::size_t> splits_;
  MeshPlan plan_;
};

}  // namespace

double rotation_about(const Eigen::Matrix3d& r, const Eigen::Matrix3d& reference, const Vec3& up) {
  const Eigen::Quaterniond d(r * reference.transpose());
  return 2.0 * std::atan2(d.vec().dot(up), d.w());
}

Eigen::Matrix3d mesh_reference_rotation(const Vec3& facing, const machines::RobotCell& cell) {
  const auto frame = [](const Vec3& x, const Vec3& z_hint, const Vec3& fallback) {
    Vec3 z = z_hint - z_hint.dot(x) * x;
    if (z.norm() < 1e-6) z = fallback - fallback.dot(x) * x;
    z.normalize();
    Eigen::Matrix3d m;
    m.col(0) = x;
    m.col(1) = z.cross(x);
    m.col(2) = z;
    return m;
  };
  const Vec3 up = -cell.nozzle_axis.normalized();
  const Eigen::Matrix3d e = frame(facing.normalized(), Vec3::UnitZ(), Vec3::UnitY());
  const Eigen::Matrix3d f = frame(up, cell.substrate_axis.normalized(), Vec3::UnitX());
  return f * e.transpose();
}

MeshPlan plan_poses_on_mesh(const slicer::Toolpath& placed, const slicer::MeshSubstrate& s,
                            const machines::RobotCell& cell, const PosePlanOptions& options) {
  PathBuilder path(s, cell, options);
  const std::vector<Target> targets = path.run(placed);
  if (targets.empty()) throw InputError("the pattern has no strokes to place on the mesh");
  MeshPlan plan = Poser(s, cell, path).run(targets);
  plan.program.substrate = s.describe();
  for (const auto& layer : placed.layers)
    plan.program.layers.push_back({layer.z_mm, layer.height_mm, 1.0});
  judge_mesh_plan(s, plan);
  return plan;
}

}  // namespace strand::post