// Idle printheads against the print through the `strand` binary (issue 33): on the shipped
// two-head profile with its idle lifts taken away (head 2 35 mm right, both tips at one height,
// "level") a part wider than the offset is refused, naming the heads, the layer and the remedy,
// and writes no file; idle_lift_mm or a narrower part is accepted; `strand check` fails a
// hand-made file whose idle head drags.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "tests/support/cli_runner.h"

namespace strand::testing {
namespace {

const std::string kShipped = std::string(STRAND_SOURCE_DIR) + "/machines/profiles/two-head-pneumatic.json";

// The shipped profile (each head held 5 mm up while idle) named `name`, with each head's
// idle lift (or only head `only`'s) set to `lift`.
void write_lifted(const std::string& path, const std::string& name, const nlohmann::json& lift, int only = -1) {
  auto p = nlohmann::json::parse(slurp(kShipped));
  p["name"] = name;
  for (std::size_t k = 0; k < p["tools"].size(); ++k) {
    if (only < 0 || static_cast<int>(k) == only) p["tools"][k]["idle_lift_mm"] = lift;
  }
  std::ofstream(path) << p.dump(1);
}

constexpr char kWide[] = "scaffold --nozzle 0.5 --gap 1 --size 50x10 --layers 2 --tools layers=0,1 ";

TEST(IdleHeadsCli, APartWiderThanTheOffsetIsRefusedUnlessTheIdleHeadIsLifted) {
  const auto dir = fresh_dir("idle-heads");
  write_lifted(dir + "/level.json", "level", 0);
  expect_input_error(run_strand(std::string(kWide) + "--machine level.json -o x.gcode", dir),
                     "tools: head 2 (T1) would drag through the print: idle while head 1 (T0) deposits layer 0");
  const auto r = run_strand(std::string(kWide) + "--machine level.json -o x.gcode", dir);
  EXPECT_NE(r.err.find("give tools[1].idle_lift_mm in machine level"), std::string::npos) << r.err;
  EXPECT_FALSE(exists(dir + "/x.gcode"));

  write_lifted(dir + "/lifted.json", "lifted", 5);
  ASSERT_EQ(run_strand(std::string(kWide) + "--machine lifted.json -o wide.gcode", dir).exit_code, 0);
  // 20 mm wide: the idle head 35 mm on never comes over it.
  ASSERT_EQ(run_strand("scaffold --nozzle 0.5 --gap 1 --size 20x10 --layers 2 --tools layers=0,1 "
                       "--machine level.json -o narrow.gcode", dir).exit_code, 0);
  // Sliced parts too, before any layer is written.
  expect_input_error(run_strand("slice " + std::string(STRAND_SOURCE_DIR) + "/samples/meshes/bone-plug.stl --scale 2.5 "
                                "--pattern scaffold --nozzle 0.5 --gap 1 --machine level.json -o plug.gcode", dir),
                     "would drag through the print");
  EXPECT_FALSE(exists(dir + "/plug.gcode"));

  // What check says of them: the wide one fails on the shipped heads, passes lifted.
  const auto bad = run_strand("check wide.gcode --machine level.json --json", dir);
  EXPECT_EQ(bad.exit_code, 1);
  const auto j = nlohmann::json::parse(bad.out);
  EXPECT_FALSE(j["ok"]);
  EXPECT_GT(j["idle_head_collisions"].get<int>(), 0);
  EXPECT_EQ(j["idle_head_collision_list"][0]["layer"], 0);
  EXPECT_EQ(j["idle_head_collision_list"][0]["tool"], 1);
  const auto good = nlohmann::json::parse(run_strand("check wide.gcode --machine lifted.json --json", dir).out);
  EXPECT_TRUE(good["ok"]) << good.dump();
  EXPECT_EQ(good["idle_head_collisions"], 0);
  EXPECT_TRUE(nlohmann::json::parse(run_strand("check narrow.gcode --machine level.json --json", dir).out)["ok"]);
}

TEST(IdleHeadsCli, TheLiftIsCheckedWhenTheProfileIsRead) {
  const auto dir = fresh_dir("idle-heads-bad");
  write_lifted(dir + "/bad.json", "bad", -1, 1);
  expect_input_error(run_strand("scaffold --nozzle 0.5 --gap 1 --size 10x10 --layers 1 --machine bad.json -o x.gcode", dir),
                     "tools[1].idle_lift_mm = -1: must be in [0, 100]");
  EXPECT_FALSE(exists(dir + "/x.gcode"));
}

// A hand-made two-head file: a 50 mm row by T0, then a short row beside it while T1 idles
// 35 mm right, on the row; then T1 prints its own rows clear of head 1.
constexpr char kDrag[] = R"(; extruder_offset = 0.000x0.000,35.000x0.000
G21
G90
M83
T0
G0 X60 Y100 Z0.4
;WIDTH:0.5
G1 X110 Y100 E5
G0 X60 Y100.3
G1 X70 Y100.3 E1
T1
G0 X40 Y120
G1 X30 Y120 E1
)";

TEST(IdleHeadsCli, CheckFlagsAHandMadeFileWhoseIdleHeadDragsAndNothingOnOneHead) {
  const auto dir = fresh_dir("idle-heads-check");
  write_lifted(dir + "/level.json", "level", 0);
  std::ofstream(dir + "/drag.gcode") << kDrag;
  const auto r = run_strand("check drag.gcode --machine level.json", dir);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.out.find("idle heads dragging through the print (1;"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("layer 0: T1 idle at (95.000, 100.300, 0.400) mm"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("while T0 deposits (line 10)"), std::string::npos) << r.out;
  write_lifted(dir + "/lifted.json", "lifted", 2);
  EXPECT_EQ(run_strand("check drag.gcode --machine lifted.json", dir).exit_code, 0);

  // One head: no idle head, nothing said or added.
  ASSERT_EQ(run_strand("scaffold --nozzle 0.5 --gap 1 --size 50x10 --layers 2 -o one.gcode", dir).exit_code, 0);
  const auto one = run_strand("check one.gcode --machine deltawasp-2040-clay --json", dir);
  EXPECT_EQ(one.exit_code, 0) << one.out;
  EXPECT_FALSE(nlohmann::json::parse(one.out).contains("idle_head_collisions"));
  EXPECT_EQ(run_strand("check one.gcode --machine deltawasp-2040-clay", dir).out.find("idle"), std::string::npos);
}

}  // namespace
}  // namespace strand::testing
