// Hexachiral specimens checked on the emitted G-code parsed back: no crossing inside a
// layer, one strand per layer, size as reported; and the input rules.
#include "patterns/hexachiral.h"
#include "patterns/registry.h"

#include <gtest/gtest.h>

#include "slicer/input_error.h"
#include "tests/patterns/chiral_test_support.h"

namespace strand::patterns {
namespace {

const nlohmann::json kThesis = {{"nozzle", 0.4}, {"cell", 5.3}, {"rows", 10},
                                {"cols", 4},     {"layers", 3}, {"grip", 10}};

chiral_testing::Emitted emit_hexa(const nlohmann::json& given) {
  return chiral_testing::emit(hexachiral_table(), find_generator("hexachiral")->generate, given);
}

double min_cell_for(const nlohmann::json& given) {
  auto p = given;
  p["cell"] = 1000.0;
  return chiral_min_cell_mm(ChiralKind::Hexa,
                            hexachiral_params_from(slicer::resolve_params(hexachiral_table(), p)));
}

TEST(Hexachiral, ThesisSpecimenIsOneStrandWithoutCrossings) {
  chiral_testing::expect_sound(emit_hexa(kThesis));
}

slicer::Toolpath wrap_hexa(const nlohmann::json& given, double period_mm) {
  return find_generator("hexachiral")
      ->generate_wrapped(slicer::resolve_params(hexachiral_table(), given), period_mm);
}

TEST(HexachiralWrap, ThesisLatticeClosesRoundTheCylinderWithGripLoops) {
  const double period = 2 * M_PI * 12.0;  // 75.4 mm: 14.2 cells of 5.3 mm -> 14 of 5.39 mm
  const slicer::Toolpath t = wrap_hexa(kThesis, period);
  testing::expect_sound_wrap(t, period);
  EXPECT_EQ(t.derived.at("cells_around").get<int>(), 14);
  EXPECT_GT(t.derived.at("filament_length_by_feature_mm").at("grip").get<double>(), 0.0);
  auto no_grip = kThesis;
  no_grip["grip"] = 0;
  const slicer::Toolpath bare = wrap_hexa(no_grip, period);
  testing::expect_sound_wrap(bare, period);
  EXPECT_FALSE(bare.derived.at("filament_length_by_feature_mm").contains("frame"))
      << "end rows have even degree: no frame";
}

TEST(HexachiralWrap, ThirtyRandomSleevesAreSoundOnTheCylinder) {
  chiral_testing::expect_random_sleeves("hexachiral", &min_cell_for, 3, 1, 1102);
}

TEST(HexachiralWrap, TooSmallACircumferenceNamesWrapAndTheLimit) {
  const double min_cell = min_cell_for(kThesis);
  try {
    wrap_hexa(kThesis, 3 * min_cell - 0.1);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("hexachiral.wrap = full: "), std::string::npos) << m;
    EXPECT_NE(m.find("at least 3 cells around"), std::string::npos) << m;
  }
}

TEST(Hexachiral, FiftyRandomValidSpecimensAreOneStrandWithoutCrossings) {
  std::mt19937 rng(5300);
  for (int i = 0; i < 50; ++i) {
    const auto given = chiral_testing::random_params(rng, &min_cell_for);
    SCOPED_TRACE(given.dump());
    chiral_testing::expect_sound(emit_hexa(given));
  }
}

TEST(Hexachiral, ThesisDefaultsGiveTheThesisNodeRadius) {
  const auto e = emit_hexa(kThesis);
  const double d = 0.4, h = 0.32;
  EXPECT_NEAR(e.toolpath.derived.at("node_radius_mm").get<double>(), 2.055 / 2 + h + d / 2, 1e-12);
  EXPECT_FALSE(e.toolpath.derived.contains("porosity_thesis"))
      << "the thesis formula is tetrachiral only";
}

TEST(Hexachiral, GripEntryFitsTheShortestFrameChord) {
  // Tiny core, one pass, cell at its limit: the frame chord is shorter than four grip lines,
  // so the grip is entered through feeders.
  nlohmann::json p = {
      {"nozzle", 0.5}, {"layer-height", 0.25}, {"node-core", 0.05}, {"node-passes", 1},
      {"grip", 2},     {"layers", 1},          {"rows", 3},         {"cols", 3}};
  p["cell"] = min_cell_for(p);
  chiral_testing::expect_sound(emit_hexa(p));
}

TEST(HexachiralParams, CellTooSmallForTheNodeNamesTheLimit) {
  auto bad = kThesis;
  bad["cell"] = 3;
  const double limit = min_cell_for(kThesis);
  try {
    find_generator("hexachiral")->generate(slicer::resolve_params(hexachiral_table(), bad));
    FAIL();
  } catch (const InputError& ex) {
    EXPECT_NE(std::string(ex.what()).find("hexachiral.cell = 3: must be >= " +
                                          slicer::short_number(limit)),
              std::string::npos)
        << ex.what();
  }
  EXPECT_LE(limit, 5.3) << "the thesis specimen is valid";
}

}  // namespace
}  // namespace strand::patterns
