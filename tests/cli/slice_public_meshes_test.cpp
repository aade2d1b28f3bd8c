// Public test meshes (tests/data/meshes-public, sources and licences in its README) sliced as
// the issue-30 bench slices them: 30 mm, scaffold, nozzle 0.6, gap 1, one perimeter or none.
// Each file must pass `strand check` (no crossing: rotor's thin beads once crossed each other),
// have no layer with material but no deposit, and miss the strand bound (1 per region + 1 per
// hole) in no more layers than today: seams down dead-end lobes (patterns/lobe_seams.h) took
// anchor from 3 to 0, goathead from 4 to 0 and spool from 13 to 3 without perimeters, and
// leaving out lone stubs in legs too narrow to join them took spool from 13 to 3 with one;
// judging the bound per part, not on the layer's totals (a part with a strand too many beside a
// sliver with none), took elephant from 2 to 0 and pinion from 9 to 7 without, 16 to 14 with;
// printing a lobe narrower than a pitch round its edge instead of its chords, keeping a slit's
// two half chords together and cutting every branch off the way between two dead ends took
// spool to 0 without and 2 with, pinion to 5 without and 13 with.
#include <gtest/gtest.h>

#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/support/cli_runner.h"

namespace strand::testing {
namespace {

TEST(SlicePublicMeshes, EachPassesCheckDepositsInEveryLayerAndHoldsTheStrandBound) {
  const std::string data = std::string(STRAND_SOURCE_DIR) + "/tests/data/meshes-public/";
  struct Case {
    std::string name;
    int perimeters;
    int layers_over;  // at most
  };
  for (const Case& c :
       {Case{"rotor.off", 1, 3}, Case{"spool.off", 1, 2}, Case{"pinion.off", 1, 12},
        Case{"anchor.off", 0, 0}, Case{"goathead.obj", 0, 0}, Case{"spool.off", 0, 0},
        Case{"elephant.off", 0, 0}, Case{"pinion.off", 0, 4}, Case{"penguin.obj", 1, 0},
        Case{"eight.off", 1, 3}}) {
    const std::string& name = c.name;
    const std::string dir = fresh_dir("public-" + name + "-" + std::to_string(c.perimeters));
    ASSERT_EQ(
        std::system(("gzip -dc '" + data + name + ".gz' > '" + dir + "/" + name + "'").c_str()), 0);
    const auto r =
        run_strand("slice " + name +
                       " --scale-to-fit 30x30x30 --pattern scaffold "
                       "--nozzle 0.6 --gap 1 --perimeters " +
                       std::to_string(c.perimeters) +
                       " --machine deltawasp-2040-clay -o part.gcode --report part.json --quiet",
                   dir);
    ASSERT_EQ(r.exit_code, 0) << name << ": " << r.err;
    const auto check = run_strand("check part.gcode --machine deltawasp-2040-clay", dir);
    EXPECT_EQ(check.exit_code, 0) << name << ":\n" << check.out;
    EXPECT_NE(check.out.find("check: OK"), std::string::npos) << name;
    const auto report = nlohmann::json::parse(slurp(dir + "/part.json"));
    EXPECT_TRUE(report.at("derived").at("empty_material_layers").empty()) << name;
    int over = 0;
    for (const auto& layer : report.at("derived").at("strands_per_region")) {
      bool layer_over = false;
      for (const auto& region : layer) {
        layer_over =
            layer_over || region.at("strands").get<int>() > 1 + region.at("holes").get<int>();
      }
      over += layer_over ? 1 : 0;
    }
    EXPECT_LE(over, c.layers_over) << name << ", " << c.perimeters << " perimeter(s)";
  }
}

}  // namespace
}  // namespace strand::testing
