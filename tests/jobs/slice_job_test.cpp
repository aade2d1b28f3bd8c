// The slice pipeline on 50 random boxes, cylinders and tori: every layer crossing-free by
// `strand check`'s own analysis, pattern strands per layer within the bound, deposited
// porosity near the pattern's own.
#include "jobs/slice_job.h"

#include <gtest/gtest.h>

#include <random>

#include "machines/profile.h"
#include "postprocess/inspect/check.h"
#include "tests/support/cli_runner.h"
#include "tests/support/mesh_shapes.h"

namespace strand::jobs {
namespace {

// Strands per layer never exceed this many per connected region of the layer (plus one
// per hole): the joins make one serpentine per monotone piece and merge most of those.
constexpr int kStrandsPerRegion = 3;

slicer::Mesh random_shape(std::mt19937& rng, int kind) {
  // Draws in named steps: the order of arguments is unspecified (GCC and clang differ), so
  // draws inside one call would give each compiler other shapes.
  std::uniform_real_distribution<double> u(0.0, 1.0);
  if (kind == 0) {
    const double z = 2 + 4 * u(rng), y = 6 + 30 * u(rng), x = 6 + 30 * u(rng);
    return testing::box_mesh(slicer::Vec3(x, y, z));
  }
  if (kind == 1) {
    const double r = 5 + 12 * u(rng);
    const double height = 2 + 4 * u(rng);
    const double hole = u(rng) < 0.5 ? 0.0 : (0.2 + 0.4 * u(rng)) * r;
    return testing::tube_mesh(r, hole, height, 64);
  }
  const double tube = 2.5 + 3 * u(rng);
  return testing::torus_mesh(tube + 3 + 12 * u(rng), tube, 64, 24);
}

TEST(SliceJob, RandomShapesAreCrossingFreeWithFewStrands) {
  std::mt19937 rng(12);  // fixed seed: the same 50 shapes every run
  const auto dir = testing::fresh_dir("slice-random");
  const machines::MachineProfile machine = machines::load_profile("deltawasp-2040-clay");
  for (int i = 0; i < 50; ++i) {
    const std::string path = dir + "/shape" + std::to_string(i) + ".stl";
    testing::write_binary_stl(random_shape(rng, i % 3), path);
    SliceSettings s;
    s.part = path;
    s.pattern_values = {{"nozzle", 0.6}, {"gap", 0.8 + 0.1 * (i % 7)}};
    s.perimeters = i % 2;
    const SliceResult r = produce_slice(s);
    post::CheckOptions o;
    o.machine = &machine;
    const post::CheckReport check = post::check_gcode(r.produced.gcode, o);
    EXPECT_TRUE(check.ok()) << path << ": " << post::to_text(check);
    EXPECT_EQ(check.crossing_count(), 0u) << path;
    const auto& d = r.toolpath.derived;
    for (std::size_t k = 0; k < d.at("regions_per_layer").size(); ++k) {
      const int regions = d.at("regions_per_layer")[k].get<int>();
      EXPECT_LE(d.at("pattern_strands_per_layer")[k].get<int>(),
                kStrandsPerRegion * std::max(regions, 1))
          << path << " layer " << k;
    }
    const double gap = d.at("porosity").get<double>() - d.at("pattern_porosity").get<double>();
    EXPECT_LT(gap, 0.02) << path
                         << ": deposited porosity is at most the pattern's (joins, perimeters add)";
    EXPECT_GT(gap, s.perimeters ? -0.45 : -0.25) << path;
  }
}

}  // namespace
}  // namespace strand::jobs
