// Thin features of a sliced part (issue 30): a fin narrower than two beads is printed as one
// centre bead when at least half a bead wide, skipped with a note when narrower; a part too
// small for the pattern still gets its walls as thin beads.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "postprocess/inspect/gcode_parser.h"
#include "tests/support/cli_runner.h"
#include "tests/support/gcode_view.h"
#include "tests/support/mesh_shapes.h"

namespace strand::testing {
namespace {

const std::string kMachine = " --machine deltawasp-2040-clay";

// A 20 mm block with a fin `fin_mm` wide standing `out_mm` out of one side (overlapping it
// by 1 mm), sliced with a 0.84 mm nozzle.
CliResult slice_finned(const std::string& dir, double fin_mm, double out_mm) {
  write_binary_stl(
      with_shell(box_mesh(slicer::Vec3(20, 20, 5)), box_mesh(slicer::Vec3(out_mm + 1, fin_mm, 5)),
                 slicer::Vec3(19, 8, 0)),
      dir + "/finned.stl");
  return run_strand(
      "slice finned.stl --nozzle 0.84 --gap 1" + kMachine + " -o f.gcode --report f.json", dir);
}

TEST(SliceCli, AThinFinOnAPartIsPrintedAsACentreBead) {
  const auto dir = fresh_dir("slice-fin");
  const auto r = slice_finned(dir, 0.5, 9);  // narrower than the bead, wider than half of it
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.find("skipped"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\n  thin beads     "), std::string::npos) << r.out;
  const auto check = run_strand("check f.gcode" + kMachine, dir);
  EXPECT_EQ(check.exit_code, 0) << check.out << check.err;
  const auto report = nlohmann::json::parse(slurp(dir + "/f.json"));
  EXPECT_TRUE(report.at("derived").at("skipped_regions").empty());
  const auto& thin = report.at("derived").at("thin_beads");
  const int layers = report.at("derived").at("layers").get<int>();
  EXPECT_EQ(thin.at("count").get<int>(), layers) << "one centre line along the fin per layer";
  // The fin outside the block runs from x = 5.5 to 14.5, y = -2 to -1.5 (part centred); its
  // bead starts a nozzle clear of the block's beads (centred 0.42 mm inside x = 5.5).
  const double per_layer = thin.at("length_mm").get<double>() / layers;
  EXPECT_GT(per_layer, 14.5 - 0.25 - (5.5 - 0.42 + 0.84) - 0.1);
  EXPECT_LT(per_layer, 14.5 - (5.5 - 0.42 + 0.84));
  // In the G-code: deposits along the fin's middle in every layer, and none elsewhere in it.
  const auto parsed = post::parse_gcode(slurp(dir + "/f.gcode"));
  std::set<int> layers_with_bead;
  for (const auto& s : deposit_segments(parsed.program)) {
    const slicer::Vec3 mid = (s.a + s.b) / 2.0;
    if (mid.x() < 5.5 + 0.42 + 0.1 || mid.y() > -1.0) continue;  // the block's own beads
    EXPECT_NEAR(s.a.y(), -1.75, 0.05) << s.a.transpose();
    EXPECT_NEAR(s.b.y(), -1.75, 0.05) << s.b.transpose();
    layers_with_bead.insert(s.layer);
  }
  EXPECT_EQ(static_cast<int>(layers_with_bead.size()), layers);
}

TEST(SliceCli, AFinNarrowerThanHalfABeadIsSkippedWithANote) {
  const auto dir = fresh_dir("slice-fin-narrow");
  const auto r = slice_finned(dir, 0.3, 14);  // under half of the 0.84 mm bead; over 4 nozzle^2
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("  skipped        "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("mm2 too thin for the 0.84 mm nozzle near ("), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("thin beads"), std::string::npos) << r.out;
  EXPECT_EQ(run_strand("check f.gcode" + kMachine, dir).exit_code, 0);
  const auto report = nlohmann::json::parse(slurp(dir + "/f.json"));
  EXPECT_EQ(report.at("derived").at("thin_beads").at("count").get<int>(), 0);
  const auto& skipped = report.at("derived").at("skipped_regions");
  ASSERT_FALSE(skipped.empty());
  double area = 0.0;
  for (const auto& s : skipped) {
    area += s.at("area_mm2").get<double>();
    // The fin outside the block runs from x = 3 to 17, y = -2 to -1.7 (part centred).
    EXPECT_NEAR(s.at("near_mm")[0].get<double>(), 10.0, 0.5);
    EXPECT_NEAR(s.at("near_mm")[1].get<double>(), -1.85, 0.3);
  }
  EXPECT_GT(area, 4.0) << "the fin's 14 x 0.3 mm outside the block, in each skipped layer";
}

// CGAL's cheese.off (CC0, tests/data/README.md), 0.1 units across, read in inches, is a
// 2.54 mm cube full of holes: with a 0.4 mm nozzle no scaffold piece fits (issue 29 refused
// it as an empty slice), but its walls between the holes, half a bead wide or more, are
// printed as thin-feature beads (issue 30).
TEST(SliceCli, ACheeseTooSmallForThePatternGetsItsWallsAsThinBeads) {
  const auto dir = fresh_dir("slice-cheese");
  const std::string cheese = std::string(STRAND_SOURCE_DIR) + "/tests/data/cheese.off";
  const auto r = run_strand("slice " + cheese + " --mesh-units in --nozzle 0.4 --gap 1" + kMachine +
                                " -o cheese.gcode --report cheese.json --quiet",
                            dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(run_strand("check cheese.gcode" + kMachine, dir).exit_code, 0);
  const auto report = nlohmann::json::parse(slurp(dir + "/cheese.json"));
  const auto& derived = report.at("derived");
  EXPECT_GT(derived.at("thin_beads").at("count").get<int>(), 0);
  EXPECT_GT(derived.at("thin_beads").at("length_mm").get<double>(), 10.0);
  EXPECT_GE(report.at("totals").at("deposit_length_mm").get<double>(),
            derived.at("thin_beads").at("length_mm").get<double>());
  // A finer nozzle fills it with the pattern too.
  const auto fine = run_strand(
      "slice " + cheese + " --mesh-units in --nozzle 0.2 --gap 0.3" + kMachine + " -o fine.gcode",
      dir);
  ASSERT_EQ(fine.exit_code, 0) << fine.err;
  EXPECT_EQ(run_strand("check fine.gcode" + kMachine, dir).exit_code, 0);
}

}  // namespace
}  // namespace strand::testing
