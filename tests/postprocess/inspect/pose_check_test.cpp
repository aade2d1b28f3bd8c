#include "postprocess/inspect/pose_check.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <sstream>

#include "machines/pose_csv.h"
#include "patterns/registry.h"
#include "postprocess/plan/produce_curved.h"
#include "slicer/input_error.h"
#include "slicer/units.h"
#include "tests/support/cli_runner.h"
#include "tests/support/sample_jobs.h"
#include "tests/postprocess/inspect/curved_file_edits.h"

namespace strand::post {
namespace {

using slicer::Vec3;
using namespace curved_edits;

const machines::MachineProfile& cell() {
  static const auto m = machines::load_profile("kuka-iiwa14-wasp-cylinder");
  return m;
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

// --- Tampering (issue 24): what a pose program promises, checked row by row ---

std::string cell(const std::string& csv, std::size_t row, int column) {
  std::string l = line_at(csv, row + 1);
  std::size_t at = 0;
  for (int c = 0; c < column; ++c) at = l.find(',', at) + 1;
  return l.substr(at, l.find_first_of(",\n", at) - at);
}

// Every row's `column` in one pass (the per-row helpers above scan from the top).
std::vector<std::string> column_of(const std::string& csv, int column) {
  std::vector<std::string> out;
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);  // the header
  while (std::getline(in, line)) {
    std::size_t at = 0;
    for (int c = 0; c < column; ++c) at = line.find(',', at) + 1;
    out.push_back(line.substr(at, line.find(',', at) - at));
  }
  return out;
}

// `csv` with every row's `column` replaced by f(row, old value), in one pass.
std::string with_column(const std::string& csv, int column,
                        const std::function<std::string(std::size_t, const std::string&)>& f) {
  std::istringstream in(csv);
  std::string line, out;
  std::getline(in, line);
  out = line + "\n";
  for (std::size_t r = 0; std::getline(in, line); ++r) {
    std::size_t at = 0;
    for (int c = 0; c < column; ++c) at = line.find(',', at) + 1;
    const std::size_t end = std::min(line.find(',', at), line.size());
    out += line.substr(0, at) + f(r, line.substr(at, end - at)) + line.substr(end) + "\n";
  }
  return out;
}

// The first row of `extrude` (0/1) after `from` whose previous row has `previous_extrude`.
std::size_t find_row(const std::string& csv, std::size_t from, const char* extrude,
                     const char* previous_extrude) {
  const auto flags = column_of(csv, 10);
  for (std::size_t r = from; r < flags.size(); ++r)
    if (flags[r] == extrude && flags[r - 1] == previous_extrude) return r;
  ADD_FAILURE() << "no such row";
  return from;
}

// Findings of every kind as text, for "which reason names this row".
std::string reasons(const PoseCheckReport& r) { return to_text(r); }

TEST(PoseCheckTampering, ADeletedOrDuplicatedRowIsFoundAtItsRow) {
  const std::string csv = thesis_csv();
  const auto deleted = check_pose_csv(without_line(csv, 501), "p.csv", cell());  // row 500
  EXPECT_FALSE(deleted.ok());
  ASSERT_GE(deleted.numbering.total, 1u);
  EXPECT_EQ(deleted.numbering.listed[0].row, 500u);
  EXPECT_NE(deleted.numbering.listed[0].what.find("index 501 after 499"), std::string::npos)
      << reasons(deleted);
  std::string dup = csv;
  dup.insert(line_start(dup, 501), line_at(dup, 501));  // row 500 twice
  const auto duplicated = check_pose_csv(dup, "p.csv", cell());
  EXPECT_FALSE(duplicated.ok());
  ASSERT_GE(duplicated.numbering.total, 1u);
  EXPECT_EQ(duplicated.numbering.listed[0].row, 501u);
  EXPECT_NE(duplicated.numbering.listed[0].what.find("index 500 after 500"), std::string::npos);
}

TEST(PoseCheckTampering, RenumberedLayersAndLapsAreFound) {
  const std::string csv = thesis_csv();
  // One row in the middle of layer 0 moved to layer 1.
  const std::size_t mid = 300;
  ASSERT_EQ(cell(csv, mid, 11), "0");
  const auto one = check_pose_csv(with_cell(csv, mid, 11, "1"), "p.csv", cell());
  EXPECT_FALSE(one.ok());
  EXPECT_TRUE(names_row(one.numbering, mid) || names_row(one.numbering, mid + 1)) << reasons(one);
  // Layer 2 renamed layer 3 on all its rows.
  const std::string renamed =
      with_column(csv, 11, [](std::size_t, const std::string& v) { return v == "2" ? "3" : v; });
  const auto skipped = check_pose_csv(renamed, "p.csv", cell());
  EXPECT_FALSE(skipped.ok());
  EXPECT_NE(reasons(skipped).find("layer 3 after layer 1"), std::string::npos) << reasons(skipped);
  // A lap number changed on one row, and a lap boundary moved by a row.
  const auto lap = check_pose_csv(with_cell(csv, mid, 12, "5"), "p.csv", cell());
  EXPECT_FALSE(lap.ok());
  EXPECT_TRUE(names_row(lap.numbering, mid)) << reasons(lap);
  std::size_t boundary = 0;
  const auto laps = column_of(csv, 12);
  for (std::size_t r = 1; r < laps.size() && !boundary; ++r)
    if (laps[r] == "1" && laps[r - 1] == "0") boundary = r;
  ASSERT_GT(boundary, 0u);
  const auto moved = check_pose_csv(with_cell(csv, boundary, 12, "0"), "p.csv", cell());
  EXPECT_FALSE(moved.ok());
  EXPECT_TRUE(names_row(moved.numbering, boundary)) << reasons(moved);
  EXPECT_NE(reasons(moved).find("the turns make this row lap 1"), std::string::npos)
      << reasons(moved);
  // Lap numbers that do not start at 0.
  const std::string shifted = with_column(
      csv, 12, [](std::size_t, const std::string& v) { return std::to_string(std::stoi(v) + 1); });
  EXPECT_TRUE(names_row(check_pose_csv(shifted, "p.csv", cell()).numbering, 0));
}

TEST(PoseCheckTampering, ATravelMarkedAsDepositingIsFound) {
  const std::string csv = thesis_csv();
  // The approach (a travel that lands on the surface) and the lift (a travel that leaves it).
  const std::size_t approach = find_row(csv, 2, "1", "0") - 1;
  const std::size_t lift = find_row(csv, 2, "0", "1");
  for (std::size_t row : {approach, lift}) {
    const auto flag_only = check_pose_csv(with_cell(csv, row, 10, "1"), "p.csv", cell());
    EXPECT_FALSE(flag_only.ok());
    EXPECT_TRUE(names_row(flag_only.extrusion, row)) << reasons(flag_only);
    // Flag and feature both changed: the geometry and the speed still say travel.
    const auto both = check_pose_csv(with_cell(with_cell(csv, row, 10, "1"), row, 13, "ligament"),
                                     "p.csv", cell());
    EXPECT_FALSE(both.ok()) << "row " << row;
    EXPECT_TRUE(names_row(both.off_surface, row) || names_row(both.speed, row)) << reasons(both);
  }
}

TEST(PoseCheckTampering, QuaternionsMustBeUnit) {
  const std::string csv = thesis_csv();
  const std::size_t row = 700;
  for (double scale : {2.0, 1.001}) {
    std::string t = csv;
    for (int c = 5; c <= 8; ++c) {
      const double q = std::stod(cell(csv, row, c));
      char buf[32];
      std::snprintf(buf, sizeof buf, "%.9f", q * scale);
      t = with_cell(t, row, c, buf);
    }
    const auto r = check_pose_csv(t, "p.csv", cell());
    EXPECT_FALSE(r.ok()) << scale;
    ASSERT_EQ(r.quaternions.total, 1u) << scale;
    EXPECT_EQ(r.quaternions.listed[0].row, row);
  }
}

TEST(PoseCheckTampering, TimesMustFitDistanceOverSpeed) {
  const std::string csv = thesis_csv();
  const std::size_t row = 900;
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6f", std::stod(cell(csv, row, 1)) + 0.5);
  const auto late = check_pose_csv(with_cell(csv, row, 1, buf), "p.csv", cell());
  EXPECT_TRUE(names_row(late.speed, row)) << reasons(late);
  const auto fast = check_pose_csv(with_cell(csv, row, 9, "12.0000"), "p.csv", cell());
  EXPECT_TRUE(names_row(fast.speed, row)) << reasons(fast);
}

TEST(PoseCheckTampering, AFileWithoutPosesIsBadInput) {
  const std::string header = line_at(thesis_csv(), 0);
  try {
    check_pose_csv(header, "p.csv", cell());
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no poses"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace strand::post
