// The lap handshake between a robot program and the extruder's G-code, run back to back
// (issue 29, item 2): a small simulator reads the signal writes and waits of the generated
// programs (URScript, KRL, RAPID and the extruder's M42/M226) and runs them on shared digital
// levels that persist between runs. Every lap wait must be released by the other side's
// signal for the same lap of the same run, whatever order the two programs run in.
#include <gtest/gtest.h>

#include <map>
#include <optional>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/cli_runner.h"

namespace strand::machines {
namespace {

// One handshake statement: set a line or wait for a level on it. `tag` is the lap it belongs
// to (-1: a reset, before lap 0 or after the last lap).
struct Op {
  bool wait = false;
  int level = 0;
  int tag = -1;
};

// The ops of a program: a line sets the current tag by the lap it names ("lap 3", ";LAP:3")
// or to -1 when it says "reset"; `set` and `wait` match the statements and give the level.
std::vector<Op> ops_of(const std::string& text, const std::regex& set, const std::regex& wait,
                       int (*level_of)(const std::string&)) {
  static const std::regex lap_re(R"((?:lap |LAP:)(\d+))");
  std::vector<Op> out;
  int tag = -1;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    std::smatch g;
    if (line.find("reset") != std::string::npos) {
      tag = -1;
    } else if (std::regex_search(line, g, lap_re)) {
      tag = std::stoi(g[1]);
    }
    if (std::regex_search(line, g, set)) out.push_back({false, level_of(g[1]), tag});
    if (std::regex_search(line, g, wait)) out.push_back({true, level_of(g[1]), tag});
  }
  return out;
}

int word_level(const std::string& s) { return s == "True" || s == "TRUE" || s == "1" ? 1 : 0; }
int pwm_level(const std::string& s) { return std::stoi(s) > 0 ? 1 : 0; }

struct Programs {
  std::vector<Op> robot, extruder;
};

Programs read_programs(const std::string& dir, const std::string& vendor) {
  Programs p;
  p.extruder = ops_of(testing::slurp(dir + "/p.extruder.gcode"), std::regex(R"(^M42 P4 S(\d+))"),
                      std::regex(R"(^M226 P3 S(\d))"), pwm_level);
  if (vendor == "urscript") {
    p.robot = ops_of(testing::slurp(dir + "/p.script"),
                     std::regex(R"(set_standard_digital_out\(\d+, (True|False)\))"),
                     std::regex(R"(while \(get_standard_digital_in\(\d+\) != (True|False)\))"),
                     word_level);
  } else if (vendor == "krl") {
    p.robot = ops_of(testing::slurp(dir + "/p.src"), std::regex(R"(\$OUT\[\d+\]=(TRUE|FALSE))"),
                     std::regex(R"(WAIT FOR \$IN\[\d+\] == (TRUE|FALSE))"), word_level);
  } else {
    p.robot = ops_of(testing::slurp(dir + "/p.mod"), std::regex(R"(SetDO \w+, ([01]);)"),
                     std::regex(R"(WaitDI \w+, ([01]))"), word_level);
  }
  return p;
}

// A level on a wire and who wrote it last.
struct Line {
  int level = 0;
  int run = -1, tag = -1;
};

// Runs `runs` back to back on `lap_line` (robot -> extruder) and `ready_line` (extruder ->
// robot), which persist between runs. `pick` chooses which side steps when both can. Returns
// the first unsynchronised wait ("" when every lap wait was released by its own lap).
std::string simulate(const std::vector<Programs>& runs, std::mt19937* rng, bool robot_first) {
  Line lap_line, ready_line;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    const auto& rob = runs[r].robot;
    const auto& ext = runs[r].extruder;
    std::size_t pr = 0, pe = 0;
    const auto step = [&](const std::vector<Op>& ops, std::size_t& pc, Line& own, Line& peer,
                          const char* who) -> std::optional<std::string> {
      const Op& op = ops[pc];
      if (!op.wait) {
        // Writing the level a line already has is no event: the line keeps its writer.
        if (own.level != op.level || own.run < 0) own = {op.level, static_cast<int>(r), op.tag};
        ++pc;
        return "";
      }
      if (peer.level != op.level) return std::nullopt;  // blocked
      ++pc;
      if (op.tag >= 0 && (peer.run != static_cast<int>(r) || peer.tag != op.tag)) {
        return std::string(who) + " run " + std::to_string(r) + " lap " + std::to_string(op.tag) +
               " released by run " + std::to_string(peer.run) + " lap " + std::to_string(peer.tag);
      }
      return "";
    };
    while (pr < rob.size() || pe < ext.size()) {
      bool robot_turn = robot_first;
      if (rng) robot_turn = (*rng)() % 2 == 0;
      if (pr == rob.size()) robot_turn = false;
      if (pe == ext.size()) robot_turn = true;
      auto res = robot_turn ? step(rob, pr, lap_line, ready_line, "robot")
                            : step(ext, pe, ready_line, lap_line, "extruder");
      if (!res) {  // blocked: the other side runs
        res =
            robot_turn
                ? (pe < ext.size() ? step(ext, pe, ready_line, lap_line, "extruder") : std::nullopt)
                : (pr < rob.size() ? step(rob, pr, lap_line, ready_line, "robot") : std::nullopt);
        if (!res) return "deadlock in run " + std::to_string(r);
      }
      if (!res->empty()) return *res;
    }
  }
  return "";
}

// Every schedule tried: each side eager in turn, and random interleavings.
std::string first_failure(const std::vector<Programs>& runs) {
  for (bool robot_first : {true, false})
    if (auto f = simulate(runs, nullptr, robot_first); !f.empty()) return f;
  for (unsigned seed = 1; seed <= 200; ++seed) {
    std::mt19937 rng(seed);
    if (auto f = simulate(runs, &rng, true); !f.empty()) return f;
  }
  return "";
}

// Without the reset before lap 0: the programs as they were before issue 29.
Programs without_reset(Programs p) {
  for (auto* ops : {&p.robot, &p.extruder})
    std::erase_if(*ops, [](const Op& op) { return op.tag < 0; });
  return p;
}

int laps_of(const Programs& p) {
  int n = 0;
  for (const Op& op : p.robot) n = std::max(n, op.tag + 1);
  return n;
}

Programs job(const std::string& machine, const std::string& vendor, int layers) {
  const std::string dir = testing::fresh_dir("handshake");
  const auto r = testing::run_strand(
      "scaffold --nozzle 0.8 --gap 1.5 --size 20x20 --layers " + std::to_string(layers) +
          " --substrate cylinder --substrate-radius 25 --substrate-length 60 --machine " + machine +
          " -o p.csv",
      dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return read_programs(dir, vendor);
}

void expect_back_to_back_runs_synchronised(const std::string& machine, const std::string& vendor) {
  // One lap per layer on this scaffold: three layers odd, two even.
  const Programs odd = job(machine, vendor, 3), even = job(machine, vendor, 2);
  ASSERT_EQ(laps_of(odd) % 2, 1) << laps_of(odd);
  ASSERT_EQ(laps_of(even) % 2, 0) << laps_of(even);
  for (const auto* p : {&odd, &even}) {
    ASSERT_FALSE(p->robot.empty());
    EXPECT_EQ(p->robot.front().tag, -1) << "the robot resets before lap 0";
    EXPECT_EQ(p->extruder.front().tag, -1) << "the extruder resets before lap 0";
  }
  EXPECT_EQ(first_failure({odd, even, odd, odd, even, even}), "") << vendor;
  // The programs without the reset: the second run's lap 0 starts on the first run's levels.
  EXPECT_NE(first_failure({without_reset(odd), without_reset(even)}), "") << vendor;
}

TEST(RobotHandshake, UrScriptAndExtruderStaySynchronisedRunAfterRun) {
  expect_back_to_back_runs_synchronised("ur10e-wasp-cylinder", "urscript");
}

TEST(RobotHandshake, KrlAndExtruderStaySynchronisedRunAfterRun) {
  expect_back_to_back_runs_synchronised("kuka-iiwa14-wasp-cylinder", "krl");
}

TEST(RobotHandshake, RapidAndExtruderStaySynchronisedRunAfterRun) {
  expect_back_to_back_runs_synchronised("abb-irb1200-wasp-cylinder", "rapid");
}

}  // namespace
}  // namespace strand::machines
