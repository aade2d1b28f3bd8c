// Flow changes in the machine's words: the profile's pressure template, a pause in each
// firmware's syntax, nothing on E-driven machines; and the profile's pressure_command checked.
#include "machines/flow_change.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "slicer/input_error.h"

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

std::string error_of(const nlohmann::json& j) {
  try {
    profile_from_json(j, "machine test.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(FlowChange, AProfilesPressureCommandNeedsAPneumaticModelAndTheFlowPlaceholder) {
  auto j = nlohmann::json::parse(R"({
    "name": "t", "description": "d",
    "kinematics": {"type": "cartesian", "min_mm": [0,0,0], "max_mm": [100,100,100]},
    "firmware": {"flavour": "marlin", "arcs": true},
    "deposition": {"model": "manual-valve", "pressure_command": ["M42 P5 S{flow}"]}})");
  EXPECT_EQ(error_of(j), "");
  EXPECT_EQ(profile_from_json(j, "t").deposition.pressure_command.size(), 1u);
  j["deposition"]["pressure_command"] = {"M42 P5 S1"};
  EXPECT_NE(error_of(j).find("deposition.pressure_command: \"M42 P5 S1\" lacks {flow}"), std::string::npos) << error_of(j);
  j["deposition"]["pressure_command"] = {"M42 P5 S{flow}\nG1 Z-10"};
  EXPECT_NE(error_of(j).find("pressure_command"), std::string::npos) << "a second line slipped in";
  j["deposition"] = {{"model", "e-volumetric"}, {"mm3_per_e", 1.0}, {"pressure_command", {"M42 S{flow}"}}};
  EXPECT_NE(error_of(j).find("only for valve or manual-valve"), std::string::npos) << error_of(j);
}

}  // namespace
}  // namespace strand::machines
