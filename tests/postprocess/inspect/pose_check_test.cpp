#include "postprocess/inspect/pose_check.h"

#include <gtest/gtest.h>

#include "machines/pose_csv.h"
#include "patterns/registry.h"
#include "postprocess/plan/produce_curved.h"
#include "slicer/input_error.h"
#include "slicer/units.h"
#include "tests/support/cli_runner.h"
#include "tests/support/sample_jobs.h"

namespace strand::post {
namespace {

using slicer::Vec3;

const machines::MachineProfile& cell() {
  static const auto m = machines::load_profile("kuka-iiwa14-wasp-cylinder");
  return m;
}

std::string produced_main(const std::string& sample, const std::string& out) {
  const auto j = nlohmann::json::parse(testing::slurp(testing::samples_dir() + "/" + sample));
  const auto* g = patterns::find_generator(j.at("generator"));
  const auto t = g->generate(slicer::resolve_params(g->table(), j.at("params")));
  return produce_curved(t, *slicer::substrate_from(j.at("substrate")),
                        machines::load_profile(j.at("machine")), 0.01, out)
      .files.front()
      .second;
}

const std::string& thesis_csv() {
  static const std::string csv = produced_main("missing-rib-cylinder.json", "p.csv");
  return csv;
}

// Replaces cell `column` of data row `row` (0-based after the header).
std::string with_cell(std::string csv, std::size_t row, int column, const std::string& value) {
  std::size_t at = 0;
  for (std::size_t k = 0; k <= row; ++k) at = csv.find('\n', at) + 1;
  for (int c = 0; c < column; ++c) at = csv.find(',', at) + 1;
  const std::size_t end = csv.find_first_of(",\n", at);
  return csv.replace(at, end - at, value);
}

TEST(PoseCheck, TheThesisProgramPasses) {
  const auto r = check_pose_csv(thesis_csv(), "p.csv", cell());
  EXPECT_TRUE(r.ok()) << to_text(r);
  ASSERT_EQ(r.layers.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_NEAR(r.layers[k].radius_mm, 20.0 + 0.96 * (k + 1), 1e-3);
    EXPECT_EQ(r.layers[k].strands, 1);
    EXPECT_TRUE(r.layers[k].crossings.empty());
  }
  EXPECT_TRUE(r.joints_checked);
  EXPECT_EQ(r.joints.poses, r.rows);
}

TEST(PoseCheck, APoseOffTheNozzleIsFoundAtItsRow) {
  const auto r = check_pose_csv(with_cell(thesis_csv(), 120, 2, "0.0"), "p.csv", cell());
  EXPECT_FALSE(r.ok());
  ASSERT_EQ(r.off_tip.total, 1u);
  EXPECT_EQ(r.off_tip.listed[0].row, 120u);
}

TEST(PoseCheck, ANormalNotFacingTheNozzleIsFound) {
  const auto r = check_pose_csv(with_cell(with_cell(thesis_csv(), 200, 17, "0.0"), 200, 19, "1.0"),
                                "p.csv", cell());
  EXPECT_EQ(r.normals.total, 1u);
  EXPECT_EQ(r.normals.listed[0].row, 200u);
}

TEST(PoseCheck, SpeedDeviationsAndADepositOffTheSurfaceAreFound) {
  auto csv = with_cell(thesis_csv(), 300, 1, "0.0");  // time runs backwards into row 300
  const auto r = check_pose_csv(csv, "p.csv", cell());
  EXPECT_GE(r.speed.total, 1u);
  const auto off = check_pose_csv(with_cell(thesis_csv(), 400, 14, "0.0"), "p.csv", cell());
  EXPECT_GE(off.off_surface.total, 1u);
}

TEST(PoseCheck, AWrongHeaderIsBadInput) {
  EXPECT_THROW(check_pose_csv("index,t\n0,1\n", "x.csv", cell()), InputError);
  EXPECT_THROW(check_pose_csv(thesis_csv(), "x.csv", machines::load_profile("marlin-rotary-a")),
               InputError);
}

// Two strands on a 10 mm radius: one runs around across the seam u = 0 (-9 to 11 deg, odd
// degrees), the other along the axis at `second_strand_deg`.
std::vector<CylinderSample> across_the_seam(double second_strand_deg) {
  const double r = 10.0;
  auto at = [&](double deg, double v) {
    return Vec3(r * std::cos(slicer::deg_to_rad(deg)), r * std::sin(slicer::deg_to_rad(deg)), v);
  };
  std::vector<CylinderSample> s;
  std::size_t id = 0;
  s.push_back({0, false, at(-10, 10), id++});
  for (double d = -9; d <= 11; d += 2) s.push_back({0, true, at(d, 10), id++});
  s.push_back({0, false, at(second_strand_deg, 5), id++});
  s.push_back({0, true, at(second_strand_deg, 15), id++});
  return s;
}

std::size_t crossings_with(double second_strand_deg) {
  PoseCheckReport r;
  check_on_cylinder(across_the_seam(second_strand_deg), 1e-3, r);
  EXPECT_EQ(r.layers.at(0).strands, 2);
  return r.crossing_count();
}

TEST(PoseCheck, CrossingsOnBothSidesOfTheSeamAreFound) {
  EXPECT_EQ(crossings_with(-4.0), 1u) << "before the seam";
  EXPECT_EQ(crossings_with(2.0), 1u) << "after the seam";
  EXPECT_EQ(crossings_with(180.0), 0u) << "the other side of the cylinder";
  EXPECT_EQ(crossings_with(20.0), 0u) << "beyond the strand";
}

// A file that deposits from its very first pose (found by curved_fuzz: no strand was open
// yet) is read as a strand starting there.
TEST(PoseCheck, ADepositFromTheFirstPoseStartsAStrand) {
  const std::string csv = with_cell(with_cell(thesis_csv(), 0, 10, "1"), 1, 10, "1");
  const auto r = check_pose_csv(csv, "p.csv", cell());
  ASSERT_FALSE(r.layers.empty());
  EXPECT_GE(r.layers[0].strands, 1);
}

TEST(PoseCheck, RotaryFilesMapBackOntoTheirCylinder) {
  const std::string g = produced_main("scaffold-cylinder-rotary.json", "r.gcode");
  ASSERT_TRUE(is_rotary_gcode(g));
  const auto m = machines::load_profile("marlin-rotary-a");
  const auto r = check_rotary_gcode(g, "r.gcode", &m);
  EXPECT_TRUE(r.ok()) << to_text(r);
  ASSERT_EQ(r.layers.size(), 4u);
  EXPECT_NEAR(r.layers[0].radius_mm, 25.0 + r.layers[1].radius_mm - r.layers[0].radius_mm, 1e-3);
  // A deposit moved off the top of the cylinder is a normal not facing the nozzle.
  const std::size_t at = g.find("\nG1 X", g.find(";LAYER:2"));
  std::string bent = g;
  bent.insert(bent.find(' ', at + 4), " Y101.000");
  EXPECT_GE(check_rotary_gcode(bent, "r.gcode", &m).normals.total, 1u);
}

}  // namespace
}  // namespace strand::post
