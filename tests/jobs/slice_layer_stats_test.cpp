// Strands per region and layers with material but no deposit, on hand-made layers: strokes
// chained end to start are one strand, a strand belongs to the part holding it, holes are
// counted, slivers narrower than half a bead are no material; the summary lines. Then whole
// slices: every layer with material deposits (a ridge narrower than a bead on top of a
// block, the sample meshes at 30 mm), checked against the written file's own layers.
#include "jobs/slice_layer_stats.h"

#include <gtest/gtest.h>

#include "jobs/slice_job.h"
#include "jobs/slice_material_bead.h"
#include "patterns/region_strands.h"
#include "tests/support/cli_runner.h"
#include "tests/support/mesh_shapes.h"

namespace strand::jobs {
namespace {

using slicer::Vec2;

slicer::Ring square(double x0, double y0, double side, bool ccw = true) {
  slicer::Ring r = {{x0, y0}, {x0 + side, y0}, {x0 + side, y0 + side}, {x0, y0 + side}};
  if (!ccw) std::reverse(r.begin(), r.end());
  return r;
}

slicer::Stroke line(const Vec2& a, const Vec2& b) {
  slicer::Stroke s;
  s.start_mm = a;
  s.segments.push_back(slicer::line_to(b, slicer::Feature::Infill));
  return s;
}

TEST(SliceLayerStats, StrandsAreCountedInTheRegionHoldingThem) {
  // Part 0: a 10 mm square with a 2 mm hole; part 1: a 10 mm square 20 mm to the right.
  const slicer::Region region = {{square(0, 0, 10), {square(4, 4, 2, false)}},
                                 {square(20, 0, 10), {}}};
  const std::vector<slicer::Stroke> strokes = {
      line({1, 1}, {9, 1}), line({9, 1}, {9, 9}),  // chained: one strand in part 0
      line({1, 9}, {3, 9}),                        // a second strand in part 0
      line({21, 1}, {29, 1}),                      // part 1
      line({21, 5}, {29, 5}), line({29, 5}, {29, 9}), line({29, 9}, {21, 9}),  // part 1 again
  };
  const auto counts = patterns::strands_per_region(region, strokes);
  ASSERT_EQ(counts.size(), 2u);
  EXPECT_EQ(counts[0], (patterns::RegionStrands{2, 1}));
  EXPECT_EQ(counts[1], (patterns::RegionStrands{2, 0}));
  // Part 0 may have two (it has a hole), part 1 one: one over, though the totals (4 strands,
  // a bound of 3) would hide it beside an empty third part.
  EXPECT_EQ(patterns::strands_over_bound(counts), 1);
  EXPECT_EQ(patterns::strands_over_bound({{2, 1}, {2, 0}, {0, 0}}), 1);
}

TEST(SliceLayerStats, ALayerWithMaterialAndNoStrokeIsNamed) {
  SliceLayerStats stats(0.6);
  const slicer::Region wide = {{square(0, 0, 5), {}}};
  const slicer::Region sliver = {{{{0, 0}, {5, 0}, {5, 0.2}, {0, 0.2}}, {}}};  // 0.2 mm < d/2
  stats.add(0, wide, {0.3, 0.3, {line({1, 1}, {4, 1})}});
  stats.add(1, wide, {0.6, 0.3, {}});
  stats.add(2, sliver, {0.9, 0.3, {}});
  stats.add(3, {}, {1.2, 0.3, {}});
  nlohmann::json derived;
  stats.write(derived);
  EXPECT_EQ(derived.at("empty_material_layers"), nlohmann::json::parse(R"([{"layer":1,"z_mm":0.6}])"));
  // The sliver is no part as a bead sees it (patterns::bead_parts): nothing to bound.
  EXPECT_EQ(derived.at("strands_per_region"),
            nlohmann::json::parse(
                R"([[{"strands":1,"holes":0}],[{"strands":0,"holes":0}],[],[]])"));
}

TEST(SliceLayerStats, SummaryLinesNameFiveLayersAndTheBound) {
  nlohmann::json d;
  d["empty_material_layers"] = nlohmann::json::array();
  d["strands_per_region"] = nlohmann::json::parse(
      R"([[{"strands":1,"holes":0},{"strands":3,"holes":2}],[{"strands":3,"holes":1}],[]])");
  EXPECT_EQ(layer_summary_lines(d),
            (std::vector<std::string>{
                "  empty layers   0",
                "  strands        at most 3 per region (bound: 1 + 1 per hole, exceeded in 1 layers: 1)"}));
  for (int k = 0; k < 6; ++k) d["strands_per_region"].push_back(nlohmann::json::parse(R"([{"strands":2,"holes":0}])"));
  EXPECT_EQ(layer_summary_lines(d)[1],
            "  strands        at most 3 per region (bound: 1 + 1 per hole, exceeded in 7 layers: 1, 3, 4, "
            "5, 6 and 2 more)");
  for (int k = 0; k < 7; ++k) d["empty_material_layers"].push_back({{"layer", k}, {"z_mm", 0.5 * k + 0.12}});
  EXPECT_EQ(layer_summary_lines(d)[0],
            "  empty layers   7 with material but no deposit: z 0.120, 0.620, 1.120, 1.620, 2.120 "
            "mm and 2 more");
}

// Every layer the report marks as having material (derived.strands_per_region lists its
// regions and empty_material_layers does not name it) deposits in the file.
void expect_every_layer_with_material_deposits(const SliceSettings& s) {
  SCOPED_TRACE(s.part);
  const SliceResult r = produce_slice(s);
  const auto& d = r.produced.report.at("derived");
  EXPECT_EQ(d.at("empty_material_layers"), nlohmann::json::array());
  const auto& layers = r.produced.report.at("layers");
  ASSERT_EQ(layers.size(), d.at("strands_per_region").size());
  for (std::size_t k = 0; k < layers.size(); ++k) {
    if (d.at("strands_per_region")[k].empty()) continue;
    EXPECT_GT(layers[k].at("deposit_length_mm").get<double>(), 0.0) << "layer " << k;
  }
}

TEST(SliceEmptyLayers, ARidgeNarrowerThanABeadOnTopGetsACentreBead) {
  // A 12 x 12 x 2.9 block with a 0.45 mm wide, 8 mm long ridge on top, in the last of six
  // layers only (nozzle 0.6, layers 0.528 mm): the ridge has material, but no perimeter
  // (centred 0.3 mm inside) nor pattern piece fits, and nothing above makes it a wall; that
  // layer was written empty (as beast.obj's top at 30 mm).
  slicer::Mesh m = testing::box_mesh(slicer::Vec3(12, 12, 2.9));
  const slicer::Mesh ridge = testing::box_mesh(slicer::Vec3(0.45, 8, 3.4));
  const int base = static_cast<int>(m.vertices_mm.size());
  for (const auto& v : ridge.vertices_mm) m.vertices_mm.push_back(v + slicer::Vec3(5.8, 2, 0));
  for (auto t : ridge.triangles) m.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  const auto dir = testing::fresh_dir("slice-ridge");
  testing::write_binary_stl(m, dir + "/ridge.stl");
  SliceSettings s;
  s.part = dir + "/ridge.stl";
  s.pattern_values = {{"nozzle", 0.6}, {"gap", 1.0}};
  s.perimeters = 1;
  expect_every_layer_with_material_deposits(s);
  const SliceResult r = produce_slice(s);
  for (const auto& layer : r.produced.report.at("layers")) {
    EXPECT_GT(layer.at("deposit_length_mm").get<double>(), 0.0) << layer.dump();
  }
}

TEST(SliceEmptyLayers, ACentreBeadRunsAlongANarrowRegion) {
  // 0.45 x 8 mm, nozzle 0.6: one bead from end to end (along the 7.7 x 0.15 mm core, and
  // across one of its ends), within a quarter bead of the centre line.
  const slicer::Region strip = {{square(20, 0, 1), {}}, {{{0, 0}, {8, 0}, {8, 0.45}, {0, 0.45}}, {}}};
  const slicer::Region narrow = {strip[1]};
  const auto beads = material_beads(narrow, 0.6, 0.5);
  ASSERT_EQ(beads.size(), 1u);
  EXPECT_NEAR(slicer::stroke_length(beads[0]), 7.7 + 0.15, 0.2);
  EXPECT_EQ(beads[0].width_mm, 0.6);
  for (const auto& seg : beads[0].segments) EXPECT_NEAR(seg.end_mm.y(), 0.225, 0.15 + 1e-6);
  // A part narrower than half a bead gets none; a 1 mm square one.
  EXPECT_TRUE(material_beads({{{{0, 0}, {8, 0}, {8, 0.25}, {0, 0.25}}, {}}}, 0.6, 0.5).empty());
  EXPECT_EQ(material_beads(strip, 0.6, 0.5).size(), 2u);
}

TEST(SliceEmptyLayers, SampleMeshesAt30MmDepositInEveryLayerWithMaterial) {
  for (const char* name : {"bone-plug.stl", "torus.stl", "spot.obj"}) {
    SliceSettings s;
    s.part = std::string(STRAND_SOURCE_DIR) + "/samples/meshes/" + name;
    s.up = std::string(name) == "spot.obj" ? "y" : "z";
    s.scale_to_fit = "30x30x30";
    s.pattern_values = {{"nozzle", 0.6}, {"gap", 1.0}};
    s.perimeters = 1;
    expect_every_layer_with_material_deposits(s);
  }
}

}  // namespace
}  // namespace strand::jobs
