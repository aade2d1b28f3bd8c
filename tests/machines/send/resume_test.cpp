// The modal state a file has set up before a line, and the preamble that restores it on
// resume: outputs (M42, M62-M65, coolant), rotary positions, E mode, feed mode, plane and
// work offset, units with the profile's mm feeds converted, homing, several words a block.
#include "machines/send/resume.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "machines/gcode_format.h"

namespace strand::machines {
namespace {

bool has(const std::vector<std::string>& v, const std::string& s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

// index of s in v, or -1
long at(const std::vector<std::string>& v, const std::string& s) {
  const auto it = std::find(v.begin(), v.end(), s);
  return it == v.end() ? -1 : it - v.begin();
}

TEST(Resume, OutputPinsValvesFansAndColdExtrusionAreRestored) {
  const auto m = load_profile("bioprinter-xyz-reprap");  // valve: M42 P0 S1 / M42 P0 S0
  const auto c = commands_of(
      "G21\nG90\nM302 S0\nM83\nG28\nG1 Z5 F600\nM42 P0 S1 ; valve open\nG1 X10 Y10 E1 F300\n"
      "M42 P3 S255\nM106 P1 S128\nM42 P0 S0\nG1 X20 E2\n",
      "f");
  const ModalState s = modal_state_before(c, 12, m);
  EXPECT_EQ(s.tool_state,
            (std::vector<std::string>{"M302 S0", "M42 P0 S0", "M42 P3 S255", "M106 P1 S128"}));
  EXPECT_EQ(s.relative_e, true);
  EXPECT_EQ(s.e, 1.0);
  // before line 11 the valve was open: the preamble closes it for the travel, then opens it
  const ModalState open = modal_state_before(c, 11, m);
  EXPECT_TRUE(has(open.tool_state, "M42 P0 S1"));
  const auto p = resume_preamble(m, open);
  const long close = at(p, m.deposition.off_gcode.front()), reopen = at(p, "M42 P0 S1");
  const long travel = at(p, "G0 X10.000 Y10.000 F" + fmt_feed(m.limits.travel_feed_mm_per_min));
  ASSERT_GE(close, 0);
  ASSERT_GE(travel, 0);
  EXPECT_LT(close, travel);
  EXPECT_LT(travel, reopen);
  EXPECT_TRUE(has(p, "M83"));
  EXPECT_TRUE(has(p, "M302 S0"));
}

TEST(Resume, DigitalOutputsAndCoolantKeepTheirLastStatePerOutput) {
  const auto c = commands_of("M64 P2\nM62 P3\nM65 P2\nM8\nM7\nM9\nM8\nG1 X1\n", "f");
  const ModalState s = modal_state_before(c, 8, MachineProfile{});
  EXPECT_EQ(s.tool_state, (std::vector<std::string>{"M65 P2", "M62 P3", "M8"}));  // mist off by M9
  EXPECT_EQ(modal_state_before(c, 6, MachineProfile{}).tool_state,
            (std::vector<std::string>{"M65 P2", "M62 P3", "M7", "M8"}));
}

TEST(Resume, RotaryPositionsAreSetWithG92) {
  const auto m = load_profile("marlin-rotary-a");
  const auto c =
      commands_of("G92 A0\nG1 X10 A90 F600\nG91\nG1 A45\nG1 A-5 X1\nG90\nG1 X12 A200\n", "f");
  const ModalState s = modal_state_before(c, 6, m);
  EXPECT_EQ(s.rotary.at('A'), 130.0);
  EXPECT_EQ(s.x, 11.0);
  EXPECT_TRUE(s.relative);
  const auto p = resume_preamble(m, s);
  EXPECT_TRUE(has(p, "G92 A130.000"));
  EXPECT_EQ(p.back(), "G91");
  EXPECT_EQ(modal_state_before(c, 8, m).rotary.at('A'), 200.0);
  // G92 A sets the count without turning anything
  const auto c2 = commands_of("G1 A30\nG92 A0\nG1 X1\n", "f");
  EXPECT_EQ(modal_state_before(c2, 3, m).rotary.at('A'), 0.0);
}

TEST(Resume, EveryWordOfABlockCountsAndInverseTimeComesBackLast) {
  const auto c = commands_of("G90 G94 G17 G21\nG55\nG18\nG93 G1 X5 F10\nG1 X6 F12\n", "f");
  const ModalState s = modal_state_before(c, 5, MachineProfile{});
  EXPECT_FALSE(s.inches);
  EXPECT_EQ(s.modes, (std::vector<std::string>{"G18", "G55"}));
  EXPECT_EQ(s.inverse_time, true);
  const auto p = resume_preamble(MachineProfile{}, s);
  EXPECT_EQ(std::vector<std::string>(p.begin(), p.begin() + 5),
            (std::vector<std::string>{"G21", "G90", "G94", "G18", "G55"}));
  EXPECT_EQ(p.back(), "G93");
  EXPECT_FALSE(std::any_of(p.begin(), p.end(),
                           [](const std::string& l) { return l.rfind("G1 F", 0) == 0; }));
  EXPECT_EQ(modal_state_before(c, 4, MachineProfile{}).inverse_time, false);
}

TEST(Resume, G90AfterM83MakesEAbsoluteAsMarlinDoes) {
  const auto c = commands_of("M83\nG1 E2\nG90\nG1 E5\nG1 X1\n", "f");
  const ModalState s = modal_state_before(c, 5, MachineProfile{});
  EXPECT_EQ(s.relative_e, false);
  EXPECT_EQ(s.e, 5.0);
  EXPECT_TRUE(has(resume_preamble(MachineProfile{}, s), "M82"));
  EXPECT_TRUE(modal_state_before(c, 3, MachineProfile{}).relative_e.value_or(false));
}

TEST(Resume, InchFilesGetTheProfilesFeedAndLiftInInches) {
  const auto m = load_profile("marlin-xyz-200");
  const auto c = commands_of("G20\nG1 X1 Y2 Z0.1 F20\nG1 X2\n", "f");
  const auto p = resume_preamble(m, modal_state_before(c, 3, m));
  const std::string feed = " F" + fmt_feed(m.limits.travel_feed_mm_per_min / 25.4);
  EXPECT_EQ(p.front(), "G20");
  EXPECT_TRUE(has(p, "G0 Z" + fmt_fixed(0.1 + m.travel_lift_mm / 25.4, 3) + feed));
  EXPECT_TRUE(has(p, "G0 X1.000 Y2.000" + feed));
  EXPECT_TRUE(has(p, "G1 F20"));
}

TEST(Resume, HomingForgetsThePositionOfTheHomedAxes) {
  const auto c = commands_of("G1 X10 Y10 Z3\nG28 X Y\nG1 Z5\nG1 X1\n", "f");
  const ModalState s = modal_state_before(c, 4, MachineProfile{});
  EXPECT_FALSE(s.x);
  EXPECT_FALSE(s.y);
  EXPECT_EQ(s.z, 5.0);
  const auto p = resume_preamble(MachineProfile{}, s);
  EXPECT_FALSE(std::any_of(p.begin(), p.end(),
                           [](const std::string& l) { return l.find(" X") != std::string::npos; }));
}

TEST(Resume, GrblGetsItsFeedAloneAndNoExtruderModes) {
  const auto m = load_profile("xy-plotter-grbl");
  const auto c = commands_of("G21 G90\nM83\nF1500\nG1 X5 Y5 M3 S1000\nG1 X6\n", "f");
  const ModalState s = modal_state_before(c, 5, m);
  EXPECT_EQ(s.f, 1500.0);
  EXPECT_TRUE(has(s.tool_state, "M3 S1000"));  // the M word alone: replaying it moves nothing
  const auto p = resume_preamble(m, s);
  EXPECT_TRUE(has(p, "F1500"));
  EXPECT_FALSE(has(p, "M83"));
}

}  // namespace
}  // namespace strand::machines
