// The start and end of a robot program (issue 29, item 1): every motion outside the laps
// planned through a clearance pose and checked for the held workpiece against the nozzle's
// cone and the extruder's body, joint moves along their joint interpolation.
#include "machines/robot_transit.h"

#include <gtest/gtest.h>

#include <cmath>

#include "machines/joint_analysis.h"
#include "machines/profile.h"
#include "machines/workpiece_pose.h"
#include "patterns/registry.h"
#include "postprocess/inspect/pose_check.h"
#include "postprocess/plan/produce_curved.h"
#include "slicer/input_error.h"
#include "slicer/mesh_io.h"
#include "slicer/units.h"
#include "tests/support/cli_runner.h"
#include "tests/support/sample_jobs.h"

namespace strand::machines {
namespace {

using slicer::Vec3;

struct ThesisJob {
  slicer::Toolpath toolpath;
  slicer::SubstrateSpec substrate;
};

ThesisJob thesis_job() {
  const auto j = nlohmann::json::parse(
      testing::slurp(testing::samples_dir() + "/missing-rib-cylinder.json"));
  const auto* g = patterns::find_generator(j.at("generator"));
  return {g->generate(slicer::resolve_params(g->table(), j.at("params"))),
          *slicer::substrate_from(j.at("substrate"))};
}

const std::vector<std::string>& arm_profiles() {
  static const std::vector<std::string> names = {"kuka-iiwa14-wasp-cylinder", "ur10e-wasp-cylinder",
                                                 "abb-irb1200-wasp-cylinder"};
  return names;
}

// The thesis job's pose program on `profile` (the whole job, so its transit plan is the one
// the writers get).
const post::CurvedProduced& produced(const std::string& profile) {
  static std::map<std::string, post::CurvedProduced> cache;
  auto it = cache.find(profile);
  if (it == cache.end()) {
    const ThesisJob j = thesis_job();
    it = cache.emplace(profile, post::produce_curved(j.toolpath, j.substrate,
                                                     load_profile(profile), 0.01, "part.csv"))
             .first;
  }
  return it->second;
}

TransitWorkpiece thesis_cylinder(const slicer::PoseProgram& p) {
  return cylinder_workpiece(20.0, 80.0, p.layers.back().offset_mm);
}

// Independent of the planner's sphere cover: the distance of a point from the cone and the
// keep-out, in the nozzle's (axial, radial) half-plane; negative inside. The nozzle is given
// in the point's frame (tip, unit axis towards the extruder).
class NozzleOutline {
 public:
  explicit NozzleOutline(const RobotCell& c) {
    const double tan_a = std::tan(slicer::deg_to_rad(c.nozzle_cone.half_angle_deg));
    len_ = c.nozzle_cone.length_mm;
    r0_ = c.nozzle_cone.tip_radius_mm;
    tan_a_ = tan_a;
    big_ = c.keep_out.radius_mm;
    top_ = len_ + c.keep_out.length_mm;
    // The union's outline in (a, r): tip (0, r0), cone top (len, r1), body (len, R) .. (len+L, R).
    const double r1 = r0_ + len_ * tan_a;
    edges_ = {{{0, 0, 0, r0_}, {0, r0_, len_, r1}, {len_, r1, len_, big_}, {len_, big_, top_, big_},
               {top_, big_, top_, 0}}};
  }
  double distance(const Vec3& tip, const Vec3& up, const Vec3& p) const {
    const Vec3 d = p - tip;
    const double a = d.dot(up), r = std::sqrt(std::max(0.0, d.squaredNorm() - a * a));
    double best = std::numeric_limits<double>::infinity();
    for (const auto& e : edges_) {
      const double vx = e[2] - e[0], vy = e[3] - e[1], wx = a - e[0], wy = r - e[1];
      const double len2 = vx * vx + vy * vy;
      const double t = len2 > 0 ? std::clamp((wx * vx + wy * vy) / len2, 0.0, 1.0) : 0.0;
      const double dx = wx - t * vx, dy = wy - t * vy;
      best = std::min(best, dx * dx + dy * dy);
    }
    best = std::sqrt(best);
    const bool inside = (a >= 0 && a <= len_ && r <= r0_ + a * tan_a_) ||
                        (a >= len_ && a <= top_ && r <= big_);
    return inside ? -best : best;
  }

 private:
  double len_, r0_, tan_a_, big_, top_;
  std::array<std::array<double, 4>, 5> edges_{};
};

// Points on the thesis cylinder's surface and end faces (workpiece frame), 1 mm apart.
std::vector<Vec3> cylinder_points(double radius, double length) {
  std::vector<Vec3> pts;
  const int around = static_cast<int>(std::ceil(2 * M_PI * radius));
  for (int k = 0; k <= static_cast<int>(length); ++k)
    for (int i = 0; i < around; ++i) {
      const double a = 2 * M_PI * i / around;
      pts.emplace_back(radius * std::cos(a), radius * std::sin(a), k);
    }
  for (double z : {0.0, length})
    for (double rr = 1.0; rr < radius; rr += 1.0)
      for (int i = 0; i < around; ++i) {
        const double a = 2 * M_PI * i / around;
        pts.emplace_back(rr * std::cos(a), rr * std::sin(a), z);
      }
  return pts;
}

// The smallest distance to the nozzle over `samples` evenly spaced points of the joint move.
double densely_sampled_joint_move(const RobotCell& c, const Joints& q0, const Joints& q1,
                                  double radius, double length, int samples) {
  const ArmModel arm = arm_model(c);
  const auto pts = cylinder_points(radius, length);
  const NozzleOutline nozzle(c);
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k <= samples; ++k) {
    const double s = static_cast<double>(k) / samples;
    const Eigen::Isometry3d w = forward_kinematics(arm, q0 + s * (q1 - q0)) * workpiece_in_flange(c);
    const Eigen::Isometry3d inv = w.inverse();
    const Vec3 tip = inv * c.nozzle_tip_mm, up = -(inv.linear() * c.nozzle_axis).normalized();
    for (const Vec3& p : pts) best = std::min(best, nozzle.distance(tip, up, p));
  }
  return best;
}

TEST(RobotTransit, TheOldTwentyMillimetreJointMoveSweepsTheThesisCylinderIntoTheNozzle) {
  // The previous programs moved by joints from home to 20 mm from the first pose. Measured
  // densely along that joint move, the workpiece enters the cone or the extruder's body on
  // every arm (the fourth review: 9-12 mm into the cone).
  // The homes the profiles shipped with then (the iiwa's has moved since: it put the
  // cylinder where the extruder stands).
  const std::map<std::string, std::array<double, 7>> old_homes = {
      {"kuka-iiwa14-wasp-cylinder", {0, 30, 0, -90, 0, -40, 0}},
      {"ur10e-wasp-cylinder", {0, -90, 90, -90, -90, 0, 0}},
      {"abb-irb1200-wasp-cylinder", {0, 0, 0, 0, 30, 0, 0}}};
  for (const auto& name : arm_profiles()) {
    MachineProfile m = load_profile(name);
    m.robot.motion.home_joints_deg = old_homes.at(name);
    const auto& p = produced(name).program;
    Joints home = Joints::Zero();
    for (int i = 0; i < 7; ++i) home[i] = slicer::deg_to_rad((*m.robot.motion.home_joints_deg)[i]);
    const Joints q20 = start_joints(m.robot, moved_along_nozzle(m.robot, p.points.front(), 20.0));
    EXPECT_LT(densely_sampled_joint_move(m.robot, home, q20, 20.0, 80.0, 400), 0.0) << name;
    // Planned with the clearance pose at 20 mm (as before), the plan refuses or moves it away.
    m.robot.motion.clearance_mm = 20.0;
    const TransitPlan plan = plan_transit(m.robot, p, thesis_cylinder(p));
    EXPECT_TRUE(!plan.ok || plan.start_clearance_mm > 20.0) << name;
  }
}

TEST(RobotTransit, TheShippedCellsStartAndEndTheThesisJobClearOfTheNozzle) {
  for (const auto& name : arm_profiles()) {
    const MachineProfile m = load_profile(name);
    const auto& out = produced(name);
    const auto& t = out.report.at("robot").at("transit");
    EXPECT_TRUE(t.at("ok").get<bool>()) << name;
    EXPECT_GE(t.at("min_clearance_mm").get<double>(), m.robot.motion.transit_margin_mm) << name;
    ASSERT_EQ(t.at("motions").size(), 6u) << name;
    for (const auto& mo : t.at("motions")) EXPECT_FALSE(mo.at("collides").get<bool>()) << name;
    EXPECT_NE(out.summary.find("outside laps   smallest clearance"), std::string::npos) << name;
  }
}

TEST(RobotTransit, EveryPlannedJointMoveIsClearBetweenItsSamplesToo) {
  // The planner's conservative advancement proves margin - 0.5 mm over the whole sweep; a
  // dense, independent sampling with an exact distance to the nozzle's outline agrees.
  for (const auto& name : arm_profiles()) {
    const MachineProfile m = load_profile(name);
    const auto& p = produced(name).program;
    const TransitPlan plan = plan_transit(m.robot, p, thesis_cylinder(p));
    ASSERT_TRUE(plan.ok) << name << ": " << plan.problem;
    const double printed = p.layers.back().offset_mm;
    EXPECT_GE(densely_sampled_joint_move(m.robot, *plan.home, plan.start_clearance_joints, 20.0,
                                         80.0, 300),
              m.robot.motion.transit_margin_mm - 0.5)
        << name;
    EXPECT_GE(densely_sampled_joint_move(m.robot, plan.end_clearance_joints, *plan.home,
                                         20.0 + printed, 80.0, 300),
              m.robot.motion.transit_margin_mm - 0.5)
        << name;
  }
}

TEST(RobotTransit, AHomeThatPutsThePartIntoTheExtruderIsRefusedNamingIt) {
  MachineProfile m = load_profile("ur10e-wasp-cylinder");
  const auto& p = produced("ur10e-wasp-cylinder").program;
  // Home: the first pose pushed 60 mm up the nozzle (the workpiece where the extruder is).
  const Joints inside = start_joints(m.robot, moved_along_nozzle(m.robot, p.points.front(), -60.0));
  std::array<double, 7> deg{};
  for (int i = 0; i < 7; ++i) deg[i] = slicer::rad_to_deg(inside[i]);
  m.robot.motion.home_joints_deg = deg;
  const TransitPlan plan = plan_transit(m.robot, p, thesis_cylinder(p));
  ASSERT_FALSE(plan.ok);
  EXPECT_EQ(plan.problem.rfind("robot.home_joints_deg: the start cannot be planned", 0), 0u)
      << plan.problem;
  EXPECT_NE(plan.problem.find("into the nozzle's cone or keep-out"), std::string::npos)
      << plan.problem;
  EXPECT_EQ(plan.problem.find('\n'), std::string::npos);
  const ThesisJob j = thesis_job();
  try {
    post::produce_curved(j.toolpath, j.substrate, m, 0.01, "part.csv");
    ADD_FAILURE() << "a colliding start was written";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), plan.problem);
  }
}

TEST(RobotTransit, AProfileWithoutHomeIsRefusedBecauseItsFirstMoveCannotBeChecked) {
  MachineProfile m = load_profile("kuka-iiwa14-wasp-cylinder");
  m.robot.motion.home_joints_deg.reset();
  const auto& p = produced("kuka-iiwa14-wasp-cylinder").program;
  const TransitPlan plan = plan_transit(m.robot, p, thesis_cylinder(p));
  ASSERT_FALSE(plan.ok);
  EXPECT_EQ(plan.problem.rfind("robot.home_joints_deg: not set", 0), 0u) << plan.problem;
}

TEST(RobotTransit, ACylinderHeldInsideTheConeIsSeenEvenWhenNoFacetIsNear) {
  // The sphere cover's centres inside the cylinder's solid count as inside (a closed mesh's
  // nearest facet alone would say "far").
  MachineProfile m = load_profile("ur10e-wasp-cylinder");
  const auto& p = produced("ur10e-wasp-cylinder").program;
  slicer::PoseProgram moved = p;
  // The whole workpiece lifted 15 mm along the nozzle: the tip is inside the cylinder.
  for (auto& pt : moved.points) pt = moved_along_nozzle(m.robot, pt, -15.0);
  const TransitPlan plan = plan_transit(m.robot, moved, thesis_cylinder(p));
  EXPECT_FALSE(plan.ok);
}

TEST(RobotTransit, StrandCheckOnTheCsvReportsTheClearanceOutsideTheLaps) {
  const auto& out = produced("ur10e-wasp-cylinder");
  std::string csv;
  for (const auto& [name, text] : out.files)
    if (name == "part.csv") csv = text;
  ASSERT_FALSE(csv.empty());
  MachineProfile m = load_profile("ur10e-wasp-cylinder");
  const post::PoseCheckReport ok = post::check_pose_csv(csv, "part.csv", m);
  ASSERT_TRUE(ok.transit_checked);
  EXPECT_TRUE(ok.ok());
  EXPECT_NE(post::to_text(ok).find("outside laps: smallest clearance"), std::string::npos);
  // Planner and check agree on the figure (the check takes the cylinder from the rows).
  EXPECT_NEAR(ok.transit.min_clearance_mm,
              out.report.at("robot").at("transit").at("min_clearance_mm").get<double>(), 0.6);
  // A hand-edited home that drives the workpiece into the extruder fails the check.
  const Joints inside = start_joints(
      m.robot, moved_along_nozzle(m.robot, out.program.points.front(), -60.0));
  std::array<double, 7> deg{};
  for (int i = 0; i < 7; ++i) deg[i] = slicer::rad_to_deg(inside[i]);
  m.robot.motion.home_joints_deg = deg;
  const post::PoseCheckReport bad = post::check_pose_csv(csv, "part.csv", m);
  EXPECT_FALSE(bad.ok());
  EXPECT_NE(post::to_text(bad).find("outside laps: COLLIDES: robot.home_joints_deg"),
            std::string::npos);
  EXPECT_FALSE(post::to_json(bad).at("transit").at("ok").get<bool>());
}

TEST(RobotTransit, EveryRobotSampleReportsItsClearanceInStrandCheck) {
  // The "done when": strand check on every robot sample states the clearance.
  for (const std::string job : {"missing-rib-cylinder.json", "tetrachiral-sphere-cap-robot.json"}) {
    const std::string dir = testing::fresh_dir("transit-sample");
    const auto made = testing::run_strand("job " + testing::samples_dir() + "/" + job + " -o part.csv", dir);
    ASSERT_EQ(made.exit_code, 0) << job << made.err;
    EXPECT_NE(made.out.find("outside laps   smallest clearance"), std::string::npos) << made.out;
    // A cylinder's CSV names no machine; a mesh's record does.
    const auto checked = testing::run_strand(
        job.find("cylinder") != std::string::npos
            ? "check part.csv --machine kuka-iiwa14-wasp-cylinder"
            : "check part.csv",
        dir);
    EXPECT_EQ(checked.exit_code, 0) << job << checked.out;
    EXPECT_NE(checked.out.find("outside laps: smallest clearance"), std::string::npos)
        << job << checked.out;
  }
}

TEST(RobotTransit, ABunnyPatchOnTheUr10eStartsClearWhereTheUprightHomeSweptItIn) {
  // The fourth review: a patch of the Stanford bunny held by the UR10e entered the cone by
  // 12.7 mm on the joint move from the upright home. The shipped home plans it clear; the
  // upright home is replanned or refused, never written as it was.
  const auto* g = patterns::find_generator("scaffold");
  const slicer::Toolpath t = g->generate(slicer::resolve_params(
      g->table(), {{"nozzle", 0.8}, {"gap", 1.5}, {"layers", 2}, {"size", "10x10"}}));
  const auto spec = *slicer::substrate_from(
      {{"type", "mesh"},
       {"mesh", std::string(STRAND_SOURCE_DIR) + "/tests/data/bunny-patch.obj"}});
  MachineProfile m = load_profile("ur10e-wasp-cylinder");
  const post::CurvedProduced out = post::produce_curved(t, spec, m, 0.01, "part.csv");
  const auto& transit = out.report.at("robot").at("transit");
  EXPECT_TRUE(transit.at("ok").get<bool>());
  EXPECT_GE(transit.at("min_clearance_mm").get<double>(), m.robot.motion.transit_margin_mm);
  m.robot.motion.home_joints_deg = std::array<double, 7>{0, -90, 90, -90, -90, 0, 0};
  m.robot.motion.clearance_mm = 20.0;  // the old programs: a joint move to 20 mm
  const TransitPlan old = plan_transit(
      m.robot, out.program,
      mesh_workpiece(slicer::read_mesh_file(std::string(STRAND_SOURCE_DIR) +
                                            "/tests/data/bunny-patch.obj"),
                     out.program.layers.back().offset_mm));
  EXPECT_TRUE(!old.ok || old.start_clearance_mm > 20.0) << old.problem;
}

}  // namespace
}  // namespace strand::machines
