// One strand per region, holes included: parts with holes slice, scaffold nozzle 0.6 gap 1,
// into at most one strand per connected region of a layer plus one per hole (perimeter loops
// counted), and every layer is crossing-free by `strand check`'s own contact search.
#include <gtest/gtest.h>

#include <algorithm>

#include "patterns/region_fill.h"
#include "patterns/registry.h"
#include "postprocess/inspect/crossings.h"
#include "slicer/mesh_io.h"
#include "slicer/mesh_slicer.h"
#include "tests/support/mesh_shapes.h"

namespace strand::patterns {
namespace {

using slicer::Vec2;
using slicer::Vec3;

struct Tally {
  int worst_excess = -1;  // strands in a region minus (1 + its holes), at worst
  std::string where;      // the first layer and region at the worst
  std::size_t crossings = 0;
  int holes = 0;  // holes seen in all layers (the shape has some)
};

// The part scaled to fit 30 mm and centred, sliced and filled layer by layer as `strand
// slice` does; strands are counted in each region they start in.
Tally fill_and_count(slicer::Mesh m, int perimeters) {
  const slicer::Box3 b0 = slicer::bounds(m);
  const Vec3 size = b0.size_mm();
  const double scale = 30.0 / std::max({size.x(), size.y(), size.z()});
  const Vec3 centre((b0.min_mm.x() + b0.max_mm.x()) / 2, (b0.min_mm.y() + b0.max_mm.y()) / 2,
                    b0.min_mm.z());
  for (Vec3& v : m.vertices_mm) v = (v - centre) * scale;
  const slicer::Box3 b = slicer::bounds(m);
  const Vec2 half(std::max(-b.min_mm.x(), b.max_mm.x()), std::max(-b.min_mm.y(), b.max_mm.y()));
  const RegionPattern p =
      region_pattern(*find_generator("scaffold"), {{"nozzle", 0.6}, {"gap", 1.0}}, half);
  const int layers = static_cast<int>(b.size_mm().z() / p.layer_height_mm);
  const std::vector<slicer::Region> regions = slicer::slice_layers(m, p.layer_height_mm, layers);
  Tally t;
  slicer::MotionProgram program;
  for (int k = 0; k < layers; ++k) {
    const LayerFill f = fill_layer(regions[static_cast<std::size_t>(k)], p, k, perimeters, half);
    for (std::size_t r = 0; r < regions[static_cast<std::size_t>(k)].size(); ++r) {
      const slicer::RegionPart& part = regions[static_cast<std::size_t>(k)][r];
      const int n = static_cast<int>(std::count_if(f.strokes.begin(), f.strokes.end(), [&](const auto& s) {
        return slicer::contains(slicer::Region{part}, s.start_mm);
      }));
      const int excess = n - 1 - static_cast<int>(part.holes.size());
      t.holes += static_cast<int>(part.holes.size());
      if (excess > t.worst_excess) {
        t.worst_excess = excess;
        t.where = "layer " + std::to_string(k) + " region " + std::to_string(r) + ": " +
                  std::to_string(n) + " strands, " + std::to_string(part.holes.size()) + " holes";
      }
    }
    const double z = (k + 1) * p.layer_height_mm;
    program.layers.push_back({z, p.layer_height_mm});
    for (const slicer::Stroke& s : f.strokes) {
      slicer::Move travel;
      travel.end_mm = Vec3(s.start_mm.x(), s.start_mm.y(), z);
      travel.layer = k;
      program.moves.push_back(travel);
      for (const auto& seg : s.segments) {
        slicer::Move mv = travel;
        mv.kind = slicer::MoveKind::Deposit;
        mv.end_mm = Vec3(seg.end_mm.x(), seg.end_mm.y(), z);
        mv.width_mm = s.width_mm;
        program.moves.push_back(mv);
      }
    }
  }
  t.crossings = post::find_contacts(program, 0.01, 1e-3).crossings.size();
  return t;
}

void expect_one_strand_per_region(const slicer::Mesh& m, const std::string& name,
                                  const std::vector<int>& perimeter_counts) {
  for (const int perimeters : perimeter_counts) {
    const Tally t = fill_and_count(m, perimeters);
    EXPECT_GT(t.holes, 0) << name;
    EXPECT_LE(t.worst_excess, 0) << name << ", " << perimeters << " perimeter(s): " << t.where;
    EXPECT_EQ(t.crossings, 0u) << name << ", " << perimeters << " perimeter(s)";
  }
}

// Two of its holes and the outside lie closer than the fill boundary reaches: their loops
// can only be printed together (a pair across the neck), as no strand end reaches them.
TEST(RegionOneStrand, PlateWithThreeHolesWithAndWithoutPerimeter) {
  expect_one_strand_per_region(testing::holed_plate_mesh(), "holed plate", {1, 0});
}

// With one perimeter, a hole's loop beside no strand end is spliced into the middle of a
// strand that runs along it (two side-by-side links); without, the joins alone hold the bound.
TEST(RegionOneStrand, Genus3BlockWithAndWithoutPerimeter) {
  expect_one_strand_per_region(testing::genus3_block_mesh(), "genus-3 block", {1, 0});
}

TEST(RegionOneStrand, SwissCheeseBlockWithAndWithoutPerimeter) {
  expect_one_strand_per_region(testing::swiss_cheese_block_mesh(), "Swiss-cheese block", {1, 0});
}

TEST(RegionOneStrand, CgalCheeseWithAndWithoutPerimeter) {
  expect_one_strand_per_region(
      slicer::read_mesh_file(std::string(STRAND_SOURCE_DIR) + "/tests/data/cheese.off"),
      "cheese.off", {1, 0});
}

}  // namespace
}  // namespace strand::patterns
