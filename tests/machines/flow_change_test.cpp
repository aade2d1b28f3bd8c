// Flow changes in the machine's words: the profile's pressure template, a pause in each
// firmware's syntax, nothing on E-driven machines (the profile's pressure_command is checked
// in profile_test).
#include "machines/flow_change.h"

#include <gtest/gtest.h>

#include <algorithm>


namespace strand::machines {
namespace {

MachineProfile pneumatic(Firmware f) {
  MachineProfile m = load_profile("deltawasp-2040-clay");
  m.firmware = f;
  return m;
}

TEST(FlowChange, APauseInEachFirmwaresWordsWhenThePressureIsSetByHand) {
  EXPECT_EQ(flow_change_gcode(pneumatic(Firmware::Marlin), 1.25, ""),
            "M117 Set flow 1.25, then resume\nM0 Set flow 1.25, then resume");
  EXPECT_EQ(flow_change_gcode(pneumatic(Firmware::Klipper), 0.8, "this ink"),
            "M117 Set flow 0.8 for this ink, then resume\nPAUSE");
  EXPECT_EQ(flow_change_gcode(pneumatic(Firmware::RepRap), 2, ""), "M291 P\"Set flow 2, then resume\" S2");
  EXPECT_EQ(flow_change_gcode(pneumatic(Firmware::Grbl), 2, ""), "M0 (Set flow 2, then resume)");
  // What the flow is for never breaks out of its line or its quotes.
  const std::string hostile = flow_change_gcode(pneumatic(Firmware::RepRap), 1, "ink \"x\"\nG1 Z-5");
  EXPECT_EQ(hostile.find('\n'), std::string::npos) << hostile;
  EXPECT_EQ(std::count(hostile.begin(), hostile.end(), '"'), 2) << hostile;
}

TEST(FlowChange, ThePressureTemplateTakesTheValueAndEDrivenMachinesNeedNoCommand) {
  MachineProfile m = load_profile("deltawasp-2040-clay-valve");
  m.deposition.pressure_command = {"M42 P5 S{flow}", "G4 P{flow}"};
  EXPECT_EQ(flow_change_gcode(m, 0.75, ""), "M42 P5 S0.75\nG4 P0.75\n; flow 0.75");
  EXPECT_TRUE(flow_is_pressure(m));
  const MachineProfile screw = load_profile("deltawasp-2040-clay-ldm");
  EXPECT_FALSE(flow_is_pressure(screw));
  EXPECT_EQ(flow_change_gcode(screw, 1.5, ""), "");
}

}  // namespace
}  // namespace strand::machines
