// Public test meshes (tests/data/meshes-public, sources and licences in its README) sliced as
// the issue-30 bench slices them: 30 mm, scaffold, nozzle 0.6, gap 1, one perimeter. Each file
// must pass `strand check` (no crossing: rotor's thin beads once crossed each other) and have
// no layer with material but no deposit.
#include <gtest/gtest.h>

#include <cstdlib>
#include <nlohmann/json.hpp>

#include "tests/support/cli_runner.h"

namespace strand::testing {
namespace {

TEST(SlicePublicMeshes, EachPassesCheckAndDepositsInEveryLayerWithMaterial) {
  const std::string data = std::string(STRAND_SOURCE_DIR) + "/tests/data/meshes-public/";
  for (const std::string name : {"rotor.off", "spool.off", "pinion.off"}) {
    const std::string dir = fresh_dir("public-" + name);
    ASSERT_EQ(std::system(("gzip -dc '" + data + name + ".gz' > '" + dir + "/" + name + "'").c_str()), 0);
    const auto r = run_strand("slice " + name + " --scale-to-fit 30x30x30 --pattern scaffold "
                              "--nozzle 0.6 --gap 1 --perimeters 1 --machine deltawasp-2040-clay "
                              "-o part.gcode --report part.json --quiet",
                              dir);
    ASSERT_EQ(r.exit_code, 0) << name << ": " << r.err;
    const auto check = run_strand("check part.gcode --machine deltawasp-2040-clay", dir);
    EXPECT_EQ(check.exit_code, 0) << name << ":\n" << check.out;
    EXPECT_NE(check.out.find("check: OK"), std::string::npos) << name;
    const auto report = nlohmann::json::parse(slurp(dir + "/part.json"));
    EXPECT_TRUE(report.at("derived").at("empty_material_layers").empty()) << name;
  }
}

}  // namespace
}  // namespace strand::testing
