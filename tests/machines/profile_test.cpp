#include "machines/profile.h"

#include <gtest/gtest.h>

#include "slicer/input_error.h"

namespace strand::machines {
namespace {

TEST(Profiles, EveryShippedProfileLoadsAndValidates) {
  const auto all = list_profiles();
  ASSERT_GE(all.size(), 2u);
  for (const auto& [name, description] : all) {
    SCOPED_TRACE(name);
    const MachineProfile p = load_profile(name);
    EXPECT_EQ(p.name, name);
    EXPECT_FALSE(description.empty());
    EXPECT_TRUE(p.source.contains("sources")) << "every profile documents its values";
  }
}

TEST(Profiles, DeltaWaspIsOneHundredMmRadiusWithoutArcs) {
  const MachineProfile p = load_profile("deltawasp-2040-clay");
  EXPECT_EQ(p.volume.kind, KinematicsKind::Delta);
  EXPECT_DOUBLE_EQ(p.volume.radius_mm, 100.0);
  EXPECT_DOUBLE_EQ(p.volume.height_mm, 400.0);
  EXPECT_FALSE(p.arcs);
  EXPECT_EQ(p.deposition.model, DepositionModel::ManualValve);
}

std::string error_of(const nlohmann::json& j) {
  try {
    profile_from_json(j, "machine test.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

nlohmann::json minimal() {
  return nlohmann::json::parse(R"({
    "name": "t", "description": "d",
    "kinematics": {"type": "cartesian", "min_mm": [0,0,0], "max_mm": [100,100,100]},
    "firmware": {"flavour": "marlin", "arcs": true},
    "deposition": {"model": "none"}})");
}

TEST(Profiles, MinimalProfileLoads) { EXPECT_EQ(error_of(minimal()), ""); }

TEST(Profiles, UnknownKeyIsNamedWithItsPath) {
  auto j = minimal();
  j["deposition"]["presure_bar"] = 1;
  EXPECT_NE(error_of(j).find("deposition.presure_bar: unknown key"), std::string::npos);
}

TEST(Profiles, WrongTypeAndRangeAreNamed) {
  auto j = minimal();
  j["firmware"]["arcs"] = "yes";
  j["travel_lift_mm"] = -3;
  const std::string e = error_of(j);
  EXPECT_NE(e.find("firmware.arcs = \"yes\": must be true or false"), std::string::npos) << e;
  EXPECT_NE(e.find("travel_lift_mm = -3: must be in [0, 100]"), std::string::npos) << e;
}

TEST(Profiles, UnknownMachineListsKnownOnes) {
  try {
    load_profile("prusa-mk4");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("deltawasp-2040-clay"), std::string::npos);
  }
}

TEST(Profiles, IssueFourProfilesShip) {
  const auto ldm = load_profile("deltawasp-2040-clay-ldm");
  EXPECT_EQ(ldm.deposition.model, DepositionModel::EVolumetric);
  EXPECT_NEAR(ldm.deposition.mm3_per_e, 3.14159265 * 0.36, 1e-6) << "1.2 mm outlet";
  EXPECT_TRUE(ldm.deposition.relative_e);
  const auto valve = load_profile("deltawasp-2040-clay-valve");
  EXPECT_EQ(valve.deposition.model, DepositionModel::Valve);
  EXPECT_GT(valve.deposition.lag_s, 0.0);
  EXPECT_DOUBLE_EQ(valve.speed_factors.at(slicer::Feature::Node), 1.1);
  const auto bio = load_profile("bioprinter-xyz-reprap");
  EXPECT_EQ(bio.firmware, Firmware::RepRap);
  EXPECT_EQ(bio.deposition.model, DepositionModel::Valve);
}

TEST(Profiles, NewKeysAreCheckedByPath) {
  auto j = minimal();
  j["speed_factors"] = {{"nodes", 1.1}, {"ligament", 40}};
  j["limits"] = {{"max_volumetric_flow_mm3_per_s", -1}};
  j["deposition"]["extrude_max_length"] = "200";
  const std::string e = error_of(j);
  EXPECT_NE(e.find("speed_factors.nodes: unknown key"), std::string::npos) << e;
  EXPECT_NE(e.find("speed_factors.ligament = 40: must be in [0.05, 10]"), std::string::npos) << e;
  EXPECT_NE(e.find("limits.max_volumetric_flow_mm3_per_s = -1"), std::string::npos) << e;
  EXPECT_NE(e.find("deposition.extrude_max_length = \"200\": must be a number"), std::string::npos) << e;
}

TEST(Profiles, GrblWithEAxisIsRejected) {
  auto j = minimal();
  j["firmware"]["flavour"] = "grbl";
  j["deposition"] = {{"model", "e-volumetric"}, {"mm3_per_e", 1.0}};
  EXPECT_NE(error_of(j).find("GRBL has no E axis"), std::string::npos);
}

TEST(Profiles, APressureCommandNeedsAPneumaticModelAndTheFlowPlaceholder) {
  auto j = minimal();
  j["deposition"] = {{"model", "manual-valve"}, {"pressure_command", {"M42 P5 S{flow}"}}};
  EXPECT_EQ(error_of(j), "");
  EXPECT_EQ(profile_from_json(j, "t").deposition.pressure_command.size(), 1u);
  j["deposition"]["pressure_command"] = {"M42 P5 S1"};
  EXPECT_NE(error_of(j).find("deposition.pressure_command: \"M42 P5 S1\" lacks {flow}"), std::string::npos) << error_of(j);
  j["deposition"]["pressure_command"] = {"M42 P5 S{flow}\nG1 Z-10"};
  EXPECT_NE(error_of(j).find("pressure_command"), std::string::npos) << "a second line slipped in";
  j["deposition"] = {{"model", "e-volumetric"}, {"mm3_per_e", 1.0}, {"pressure_command", {"M42 S{flow}"}}};
  EXPECT_NE(error_of(j).find("only for valve or manual-valve"), std::string::npos) << error_of(j);
}

TEST(Profiles, ToolsAreCheckedByTheirIndexAndTheirChangeByFirmware) {
  auto j = minimal();
  j["tools"] = nlohmann::json::parse(R"([{"name": "a"}, {"name": "b", "offset_mm": [30, 0, -1], "nozzle_mm": 0.4,
      "deposition": {"model": "valve", "on_gcode": ["M42 P7 S255"], "off_gcode": ["M42 P7 S0"]}}])");
  ASSERT_EQ(error_of(j), "");
  const auto p = profile_from_json(j, "t");
  EXPECT_EQ(tool_count(p), 2);
  EXPECT_EQ(tool_deposition(p, 1).model, DepositionModel::Valve);
  EXPECT_EQ(tool_deposition(p, 0).model, DepositionModel::None) << "the machine's deposition";
  EXPECT_EQ(tool_offset(p, 1), Vec3(30, 0, -1));
  EXPECT_EQ(tool_count(profile_from_json(minimal(), "t")), 1);

  j["tools"][1]["colour"] = "red";
  j["tools"][0]["offset_mm"] = {1, 0, 0};
  const std::string e = error_of(j);
  EXPECT_NE(e.find("tools[1].colour: unknown key"), std::string::npos) << e;
  j["tools"][1].erase("colour");
  EXPECT_NE(error_of(j).find("tools[0].offset_mm: must be [0, 0, 0]"), std::string::npos) << error_of(j);
  j["tools"][0].erase("offset_mm");
  j["tools"][1]["deposition"].erase("on_gcode");
  EXPECT_NE(error_of(j).find("tools[1]: deposition.on_gcode/off_gcode: missing"), std::string::npos) << error_of(j);
  j["tools"] = nlohmann::json::array();
  EXPECT_NE(error_of(j).find("tools = []: must be a list of 1 to 16 objects"), std::string::npos) << error_of(j);
  auto grbl = minimal();
  grbl["firmware"]["flavour"] = "grbl";
  grbl["tools"] = nlohmann::json::parse(R"([{"name": "a"}, {"name": "b"}])");
  EXPECT_NE(error_of(grbl).find("tool_change_gcode: missing (GRBL has no T command"), std::string::npos) << error_of(grbl);
  auto lone = minimal();
  lone["tool_change_gcode"] = {"T{tool}"};
  EXPECT_NE(error_of(lone).find("tool_change_gcode: only with a tools list"), std::string::npos);
}

}  // namespace
}  // namespace strand::machines
