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

TEST(PreviewScene, ColoursAreDistinctPerFeatureAndRunAlongLayers) {
  EXPECT_NE(hex_colour(feature_colour(slicer::Feature::Wall)), hex_colour(feature_colour(slicer::Feature::Infill)));
  EXPECT_EQ(hex_colour({1, 0, 0.5}), "#ff0080");
  EXPECT_GT(layer_colour(9, 10).r, layer_colour(0, 10).r);
  EXPECT_LT(layer_colour(9, 10).b, layer_colour(0, 10).b);
}

}  // namespace
}  // namespace strand::post
