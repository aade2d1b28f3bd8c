// Preview scenes: polylines split by layer, feature and travel; arcs flattened on their
// circle; bounds from deposits only; colours.
#include "postprocess/preview/preview_scene.h"

#include <gtest/gtest.h>

#include "postprocess/inspect/gcode_parser.h"

namespace strand::post {
namespace {

const char* kProgram =
    ";LAYER:0\n;Z:0.5\nG0 X-50 Y-50 Z0.5\nG0 X10 Y0\n"
    ";TYPE:Perimeter\n;FEATURE:wall\nG1 X20 Y0 E1\nG2 X10 Y0 I-5 J0 E2\n"   // half circle r 5 around (15, 0)
    ";TYPE:Solid infill\n;FEATURE:infill\nG1 X10 Y5 E3\n"
    ";LAYER:1\n;Z:1\nG0 X10 Y5 Z1\nG1 X12 Y5 E4\n";

TEST(PreviewScene, SplitsByTravelFeatureAndLayer) {
  const auto s = preview_scene(parse_gcode(kProgram).program, 0.01);
  std::vector<std::string> kinds;
  for (const auto& p : s.paths) {
    kinds.push_back((p.travel ? std::string("travel") : slicer::to_string(p.feature)) + "@" + std::to_string(p.layer));
  }
  EXPECT_EQ(kinds, (std::vector<std::string>{"travel@0", "wall@0", "infill@0", "travel@1", "infill@1"}));
  EXPECT_EQ(s.layer_z_mm, (std::vector<double>{0.5, 1.0}));
}

TEST(PreviewScene, ArcsAreFlattenedOnTheirCircle) {
  const auto s = preview_scene(parse_gcode(kProgram).program, 0.01);
  const auto& wall = s.paths.at(1).points_mm;
  ASSERT_GT(wall.size(), 10u);  // line end + many chords
  for (std::size_t i = 2; i < wall.size(); ++i) {
    EXPECT_NEAR((wall[i].head<2>() - slicer::Vec2(15, 0)).norm(), 5.0, 1e-9);
  }
  EXPECT_LT(wall.back().y(), 5.0 + 1e-9);
}

TEST(PreviewScene, BoundsCoverDepositsNotTravel) {
  const auto s = preview_scene(parse_gcode(kProgram).program, 0.01);
  EXPECT_NEAR(s.min_mm.x(), 10.0, 1e-9);  // the travel from (-50, -50) is left out
  EXPECT_NEAR(s.max_mm.x(), 20.0, 1e-9);
  EXPECT_NEAR(s.max_mm.y(), 5.0, 1e-6);   // top of the arc and the infill end
}

TEST(PreviewScene, PurgeLinesBeforeTheFirstLayerAreLeftOutOfTheBounds) {
  // PrusaSlicer's intro line: deposits at y = -3 before the first ;LAYER_CHANGE
  const char* kPurge =
      "G1 Z0.3\nG1 X0 Y-3 F1000\nG1 X60 Y-3 E9\nG1 X100 Y-3 E12.5\n"
      ";LAYER_CHANGE\n;Z:0.3\nG1 X40 Y40 F3000\nG1 X50 Y40 E13\nG1 X50 Y50 E14\n";
  const auto s = preview_scene(parse_gcode(kPurge).program, 0.01);
  ASSERT_EQ(s.paths.front().layer, -1);
  EXPECT_NEAR(s.min_mm.x(), 40.0, 1e-9);
  EXPECT_NEAR(s.min_mm.y(), 40.0, 1e-9);
  EXPECT_NEAR(s.max_mm.x(), 50.0, 1e-9);
  EXPECT_FALSE(is_3d(s));
}

TEST(PreviewScene, PathsLeavingTheirLayerPlaneMakeA3dScene) {
  // a vase-mode spiral: z rises along the deposit
  const char* kSpiral = ";LAYER:0\n;Z:0.2\nG0 X0 Y0 Z0.2\nG1 X10 Y0 Z0.3 E1\nG1 X10 Y10 Z0.4 E2\n";
  EXPECT_TRUE(is_3d(preview_scene(parse_gcode(kSpiral).program, 0.01)));
  EXPECT_FALSE(is_3d(preview_scene(parse_gcode(kProgram).program, 0.01)));
}

TEST(PreviewScene, FromPathsKeepsTheSubstrateAndBoundsTheDeposits) {
  slicer::TriangleMesh plate;
  plate.vertices_mm = {{-50, -50, 0}, {50, -50, 0}, {50, 50, 0}};
  plate.triangles = {{0, 1, 2}};
  std::vector<PreviewPath> paths = {
      {0, slicer::Feature::Ligament, false, {{0, 0, 0.4}, {10, 0, 0.4}}},
      {0, slicer::Feature::Ligament, true, {{10, 0, 0.4}, {30, 30, 5}}},
      {1, slicer::Feature::Node, false, {{30, 30, 0.8}, {31, 32, 0.8}}}};
  const auto s = scene_from_paths(paths, {0.4, 0.8}, plate, 0.5);
  EXPECT_EQ(s.paths, paths);
  EXPECT_EQ(s.substrate.vertices_mm.size(), 3u);
  EXPECT_EQ(s.layer_value, "offset");
  EXPECT_EQ(s.layer_z_mm, (std::vector<double>{0.4, 0.8}));
  EXPECT_EQ(s.bead_width_mm, 0.5);
  EXPECT_NEAR(s.max_mm.y(), 32.0, 1e-12) << "deposits only";
  EXPECT_NEAR(s.max_mm.z(), 0.8, 1e-12) << "not the travel's 5";
  EXPECT_TRUE(is_3d(s)) << "a substrate is drawn in 3D";
  paths.push_back({1, slicer::Feature::Node, false, {{0, 0, 0}}});
  EXPECT_THROW(scene_from_paths(paths, {0.4, 0.8}, plate, 0.5), std::invalid_argument);
}

TEST(PreviewScene, ColoursAreDistinctPerFeatureAndRunAlongLayers) {
  EXPECT_NE(hex_colour(feature_colour(slicer::Feature::Wall)), hex_colour(feature_colour(slicer::Feature::Infill)));
  EXPECT_EQ(hex_colour({1, 0, 0.5}), "#ff0080");
  EXPECT_GT(layer_colour(9, 10).r, layer_colour(0, 10).r);
  EXPECT_LT(layer_colour(9, 10).b, layer_colour(0, 10).b);
}

}  // namespace
}  // namespace strand::post
