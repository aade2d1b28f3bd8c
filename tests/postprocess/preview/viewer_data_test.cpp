// The viewer's layer blocks: bytes decode back to the moves read, layer stats agree with the
// estimate, layer ranges are byte ranges, and 3D scenes carry their substrate.
#include "postprocess/preview/viewer_data.h"

#include <gtest/gtest.h>

#include <string>

#include "postprocess/inspect/gcode_parser.h"
#include "postprocess/plan/estimate.h"
#include "postprocess/preview/viewer_html.h"
#include "slicer/input_error.h"

namespace strand::post {
namespace {

using slicer::Vec3;

// Two layers: a travel, two wall deposits with E, an infill arc (G2), a second layer.
const char* kGcode =
    "G21\nG90\nM83\n"
    ";LAYER:0\n;Z:0.5\n"
    "G0 X0 Y0 Z0.5 F3000\n"         // line 6: travel
    ";TYPE:External perimeter\n"
    "G1 X10 Y0 E2 F600\n"           // line 8: 10 mm, 0.2 E/mm
    "G1 X10 Y10 E1\n"               // line 9: 10 mm, 0.1 E/mm
    ";TYPE:Solid infill\n"
    "G2 X20 Y10 I5 J0 E3 F900\n"    // line 11: a half circle, as chords
    ";LAYER:1\n;Z:1.0\n"
    "G0 X0 Y0 Z1 F3000\n"           // line 14
    "G1 X5 Y0 E1 F600\n";           // line 15

ViewerData data() { return viewer_data_from_gcode(kGcode, nullptr, 0.01, "t.gcode"); }

TEST(ViewerData, BlocksDecodeBackToTheMovesRead) {
  const ViewerData d = data();
  ASSERT_EQ(d.layers.size(), 2u);
  const auto l0 = decode_viewer_block(viewer_blocks(d, 0, 0), d.layers[0].segments);
  ASSERT_GT(l0.size(), 4u) << "the arc is drawn as several chords";
  EXPECT_EQ(d.layers[0].moves, 4u);
  EXPECT_TRUE(l0[0].kind & kViewerTravelBit);
  EXPECT_EQ(l0[0].line, 6u);
  EXPECT_EQ(l0[1].from_mm, Vec3(0, 0, 0.5));
  EXPECT_EQ(l0[1].to_mm, Vec3(10, 0, 0.5));
  EXPECT_EQ(l0[1].kind, static_cast<int>(slicer::Feature::Wall));
  EXPECT_FLOAT_EQ(l0[1].feed_mm_per_min, 600.0f);
  EXPECT_FLOAT_EQ(l0[1].e_per_mm, 0.2f);
  EXPECT_FLOAT_EQ(l0[2].e_per_mm, 0.1f);
  EXPECT_EQ(l0[2].line, 9u);
  const ViewerSegment& last = l0.back();
  EXPECT_EQ(last.kind, static_cast<int>(slicer::Feature::Infill));
  EXPECT_EQ(last.line, 11u);
  EXPECT_NEAR(last.to_mm.x(), 20.0, 1e-5);
  EXPECT_NEAR(last.to_mm.y(), 10.0, 1e-5);
  EXPECT_NEAR(last.e_per_mm, 3.0 / (5.0 * M_PI), 1e-4) << "E over the arc's length";
  for (std::size_t i = 1; i < l0.size(); ++i) EXPECT_EQ(l0[i].from_mm, l0[i - 1].to_mm) << i;
  const auto l1 = decode_viewer_block(viewer_blocks(d, 1, 1), d.layers[1].segments);
  ASSERT_EQ(l1.size(), 2u);
  EXPECT_EQ(l1[1].to_mm, Vec3(5, 0, 1));
  EXPECT_EQ(l1[1].line, 15u);
}

TEST(ViewerData, LayerStatsAreTheEstimatesAndTheFilesE) {
  const ViewerData d = data();
  const Estimate e = estimate(parse_gcode(kGcode).program);
  ASSERT_EQ(e.layers.size(), d.layers.size());
  for (std::size_t i = 0; i < d.layers.size(); ++i) {
    EXPECT_EQ(d.layers[i].strands, e.layers[i].strands) << i;
    EXPECT_DOUBLE_EQ(d.layers[i].deposit_length_mm, e.layers[i].deposit_length_mm) << i;
    EXPECT_DOUBLE_EQ(d.layers[i].time_s, e.layers[i].time_naive_s) << i;
  }
  EXPECT_DOUBLE_EQ(d.layers[0].e, 6.0);
  EXPECT_DOUBLE_EQ(d.layers[1].e, 1.0);
  EXPECT_DOUBLE_EQ(d.layers[1].z_mm, 1.0);
  EXPECT_FLOAT_EQ(d.max_feed_mm_per_min, 900.0f);
  EXPECT_EQ(d.min_mm, Vec3(0, 0, 0.5)) << "bounds of the deposits";
}

TEST(ViewerData, ARangeOfLayersIsOneByteRangeAlignedForTypedArrays) {
  const ViewerData d = data();
  EXPECT_EQ(d.layers[1].offset, viewer_block_bytes(d.layers[0].segments));
  EXPECT_EQ(d.layers[1].offset % 4, 0u);
  EXPECT_EQ(viewer_blocks(d, 0, 1), std::string_view(d.blocks));
  const nlohmann::json index = viewer_index(d);
  EXPECT_EQ(index.at("layers").at(1).at("offset"), d.layers[1].offset);
  EXPECT_EQ(index.at("segments"), d.layers[0].segments + d.layers[1].segments);
  EXPECT_EQ(index.at("features").at(static_cast<int>(slicer::Feature::Wall)), "wall");
  EXPECT_FALSE(index.contains("substrate"));
}

TEST(ViewerData, AFileWithoutMovesIsRefused) {
  EXPECT_THROW(viewer_data_from_gcode("G21\n; nothing\n", nullptr, 0.01, "empty.gcode"), InputError);
}

TEST(ViewerData, ASceneKeepsItsSubstrateAndLayers) {
  std::vector<PreviewPath> paths(2);
  paths[0].layer = 0, paths[0].points_mm = {Vec3(0, 0, 1), Vec3(3, 4, 1)};
  paths[1].layer = 1, paths[1].travel = true, paths[1].points_mm = {Vec3(3, 4, 1), Vec3(0, 0, 2), Vec3(0, 0, 3)};
  slicer::TriangleMesh mesh;
  mesh.vertices_mm = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  mesh.triangles = {{0, 1, 2}};
  const ViewerData d = viewer_data_from_scene(scene_from_paths(paths, {0.5, 1.0}, mesh, 0.4), "p.csv");
  ASSERT_EQ(d.layers.size(), 2u);
  EXPECT_EQ(d.layers[0].strands, 1);
  EXPECT_DOUBLE_EQ(d.layers[0].deposit_length_mm, 5.0);
  EXPECT_EQ(d.layers[1].segments, 2u);
  EXPECT_DOUBLE_EQ(d.layers[1].z_mm, 1.0);
  const nlohmann::json index = viewer_index(d);
  EXPECT_EQ(index.at("layer_value"), "offset");
  EXPECT_EQ(index.at("substrate").at("t"), nlohmann::json({0, 1, 2}));
}

TEST(ViewerHtml, OneFileWithTheScriptAndTheData) {
  const std::string html = render_viewer_html(data(), "a</script>.gcode");
  EXPECT_NE(html.find("id=\"strand-view-blocks\""), std::string::npos);
  EXPECT_EQ(html.find("a</script>"), std::string::npos) << "the title is escaped";
  EXPECT_NE(html.find("three"), std::string::npos) << "three.js is inside";
  EXPECT_EQ(html.find("<script src"), std::string::npos) << "nothing fetched from the network";
}

}  // namespace
}  // namespace strand::post
