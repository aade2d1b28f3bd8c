// The slice job on every core: the layers cut in parallel are those slice_layers cuts, the
// thin features found in parallel are print_thin_features' and the thin walls skipped on many
// threads those skipped on one, the file and report of a parallel run are the bytes of a
// one-thread run (meshes with holes and without, with thin beads and skipped walls, scaffold
// and tetrachiral, with and without perimeters), and a thread count out of range is refused
// naming slice.threads.
#include "jobs/slice_parallel.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <cstdlib>

#include "jobs/slice_job.h"
#include "jobs/slice_thin_walls.h"
#include "slicer/input_error.h"
#include "tests/support/cli_runner.h"
#include "tests/support/mesh_shapes.h"

namespace strand::jobs {
namespace {

TEST(SliceParallel, CutLayersAreTheSerialSlices) {
  for (const slicer::Mesh& m : {testing::torus_mesh(12.0, 4.0, 96, 32), testing::swiss_cheese_block_mesh()}) {
    slicer::ContourStats serial_stats, parallel_stats;
    const auto serial = slicer::slice_layers(m, 0.3, 40, &serial_stats);
    const auto parallel = cut_layers(m, 0.3, 40, &parallel_stats);
    EXPECT_EQ(serial, parallel);
    EXPECT_EQ(serial_stats.gaps_closed, parallel_stats.gaps_closed);
    EXPECT_EQ(serial_stats.widest_gap_mm, parallel_stats.widest_gap_mm);
    EXPECT_EQ(serial_stats.dropped_pieces, parallel_stats.dropped_pieces);
  }
}

// A 20 x 20 x 5 mm block with fins for a 0.84 mm nozzle standing out of two sides (each
// overlapping it by 1 mm): 0.5 mm wide and 9 mm out, 5 mm tall (a centre bead in every layer),
// and 0.3 mm wide and 14 mm out, 3 mm tall (under half a bead: skipped, over 4 nozzle^2).
slicer::Mesh finned_block_mesh() {
  slicer::Mesh m = testing::box_mesh(slicer::Vec3(20, 20, 5));
  const auto add = [&m](const slicer::Mesh& b, const slicer::Vec3& offset) {
    const int base = static_cast<int>(m.vertices_mm.size());
    for (const auto& v : b.vertices_mm) m.vertices_mm.push_back(v + offset);
    for (const auto& t : b.triangles) m.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  };
  add(testing::box_mesh(slicer::Vec3(10, 0.5, 5)), slicer::Vec3(19, 8, 0));
  add(testing::box_mesh(slicer::Vec3(15, 0.3, 3)), slicer::Vec3(-14, 12, 0));
  return m;
}

TEST(SliceParallel, ThinFeaturesAndSkippedWallsAreThoseOfOneThread) {
  const double nozzle = 0.84, h = 0.5;
  const std::vector<slicer::Region> cut = cut_layers(finned_block_mesh(), h, 10, nullptr);
  std::vector<slicer::Region> serial = cut, parallel = cut;
  const patterns::PartThinBeads one = patterns::print_thin_features(serial, nozzle, h);
  patterns::PartThinBeads many;
  tbb::task_arena(4).execute([&] { many = thin_features_in_parallel(parallel, nozzle, h); });
  EXPECT_EQ(one.count, 10) << "the wide fin's centre line in each layer";
  EXPECT_EQ(many.count, one.count);
  EXPECT_EQ(many.length_mm, one.length_mm);
  EXPECT_TRUE(many.per_layer == one.per_layer);
  EXPECT_TRUE(parallel == serial);
  EXPECT_FALSE(parallel == cut) << "the fin's strip left the layers it is printed in";

  patterns::RegionPattern p;
  p.nozzle_mm = nozzle;
  p.layer_height_mm = h;
  nlohmann::json skipped_one = nlohmann::json::array(), skipped_many = nlohmann::json::array();
  std::vector<std::string> notes_one, notes_many;
  tbb::task_arena(1).execute([&] { notes_one = skip_thin_walls(serial, p, skipped_one); });
  tbb::task_arena(4).execute([&] { notes_many = skip_thin_walls(parallel, p, skipped_many); });
  ASSERT_EQ(notes_one.size(), 1u) << "the narrow fin, from the bottom to 3 mm";
  EXPECT_EQ(notes_many, notes_one);
  EXPECT_EQ(skipped_many.dump(), skipped_one.dump());
  EXPECT_TRUE(parallel == serial);
}

struct Case {
  std::string mesh;
  nlohmann::json pattern_values;
  std::string pattern;
  int perimeters;
  bool thin = false;  // the part has thin beads and skipped walls
};

TEST(SliceParallel, ParallelAndSerialRunsWriteTheSameBytes) {
  const auto dir = testing::fresh_dir("slice-parallel");
  testing::write_binary_stl(testing::torus_mesh(12.0, 5.0, 96, 32), dir + "/torus.stl");
  testing::write_binary_stl(testing::swiss_cheese_block_mesh(), dir + "/cheese.stl");
  testing::write_binary_stl(testing::holed_plate_mesh(), dir + "/plate.stl");
  testing::write_binary_stl(finned_block_mesh(), dir + "/finned.stl");
  const nlohmann::json scaffold = {{"nozzle", 0.6}, {"gap", 1.0}};
  const nlohmann::json chiral = {{"nozzle", 0.4}, {"cell", 5.0}, {"node-core", 1.0}};
  const std::vector<Case> cases = {
      {dir + "/torus.stl", scaffold, "scaffold", 1},
      {dir + "/cheese.stl", scaffold, "scaffold", 0},
      {dir + "/plate.stl", chiral, "tetrachiral", 1},
      {dir + "/cheese.stl", chiral, "tetrachiral", 0},
      {std::string(STRAND_SOURCE_DIR) + "/samples/meshes/bone-plug.stl", scaffold, "scaffold", 1},
      {dir + "/finned.stl", {{"nozzle", 0.84}, {"gap", 1.0}}, "scaffold", 1, true},
  };
  for (const Case& c : cases) {
    SliceSettings s;
    s.part = c.mesh;
    s.pattern = c.pattern;
    s.pattern_values = c.pattern_values;
    s.perimeters = c.perimeters;
    s.threads = 1;
    const SliceResult serial = produce_slice(s);
    s.threads = 4;  // more threads than cores: the fills finish out of order
    const SliceResult parallel = produce_slice(s);
    SCOPED_TRACE(c.mesh + " " + c.pattern + " perimeters " + std::to_string(c.perimeters));
    EXPECT_GT(serial.produced.gcode.size(), 1000u);
    EXPECT_TRUE(serial.produced.gcode == parallel.produced.gcode);
    EXPECT_EQ(serial.produced.report.dump(), parallel.produced.report.dump());
    if (c.thin) {
      EXPECT_GT(serial.toolpath.derived.at("thin_beads").at("count").get<int>(), 0);
      EXPECT_FALSE(serial.toolpath.derived.at("skipped_regions").empty());
    }
  }
}

// A public mesh (tests/data/meshes-public) at 30 mm as the bench slices it, with thin beads
// in many layers: the same bytes on one thread and on four.
TEST(SliceParallel, APublicMeshWithThinBeadsWritesTheSameBytes) {
  const auto dir = testing::fresh_dir("slice-parallel-public");
  const std::string data = std::string(STRAND_SOURCE_DIR) + "/tests/data/meshes-public/";
  ASSERT_EQ(std::system(("gzip -dc '" + data + "rotor.off.gz' > '" + dir + "/rotor.off'").c_str()), 0);
  SliceSettings s;
  s.part = dir + "/rotor.off";
  s.scale_to_fit = "30x30x30";
  s.pattern_values = {{"nozzle", 0.6}, {"gap", 1.0}};
  s.perimeters = 1;
  s.threads = 1;
  const SliceResult serial = produce_slice(s);
  s.threads = 4;
  const SliceResult parallel = produce_slice(s);
  EXPECT_GT(serial.toolpath.derived.at("thin_beads").at("count").get<int>(), 1);
  EXPECT_TRUE(serial.produced.gcode == parallel.produced.gcode);
  EXPECT_EQ(serial.produced.report.dump(), parallel.produced.report.dump());
}

TEST(SliceParallel, ThreadsOutOfRangeAreRefused) {
  for (const int n : {0, -1, 257}) {
    SliceSettings s;
    s.part = std::string(STRAND_SOURCE_DIR) + "/samples/meshes/bone-plug.stl";
    s.pattern_values = {{"nozzle", 0.6}, {"gap", 1.0}};
    s.threads = n;
    try {
      produce_slice(s);
      ADD_FAILURE() << n << " threads accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()), "slice.threads = " + std::to_string(n) + ": must be in [1, 256]");
    }
  }
  const auto r = testing::run_strand(std::string("slice ") + STRAND_SOURCE_DIR +
                                     "/samples/meshes/bone-plug.stl --nozzle 0.6 --gap 1 "
                                     "--threads 300 -o x.gcode");
  testing::expect_input_error(r, "slice.threads = 300: must be in [1, 256]");
}

}  // namespace
}  // namespace strand::jobs
