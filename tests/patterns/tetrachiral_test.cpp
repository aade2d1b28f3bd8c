// Tetrachiral specimens checked on the emitted G-code parsed back: no crossing inside a
// layer, one strand per layer, size as reported; and the input rules.
#include "patterns/tetrachiral.h"
#include "patterns/registry.h"

#include <gtest/gtest.h>

#include <cmath>

#include "slicer/input_error.h"
#include "tests/patterns/chiral_test_support.h"

namespace strand::patterns {
namespace {

using chiral_testing::emit;

const nlohmann::json kThesis = {{"nozzle", 0.5}, {"cell", 10},  {"rows", 6},
                                {"cols", 2},     {"layers", 3}, {"grip", 10}};

chiral_testing::Emitted emit_tetra(const nlohmann::json& given) {
  return emit(tetrachiral_table(), find_generator("tetrachiral")->generate, given);
}

double min_cell_for(const nlohmann::json& given) {
  auto p = given;
  p["cell"] = 1000.0;
  return chiral_min_cell_mm(
      ChiralKind::Tetra, tetrachiral_params_from(slicer::resolve_params(tetrachiral_table(), p)));
}

TEST(Tetrachiral, ThesisSpecimenIsOneStrandWithoutCrossings) {
  chiral_testing::expect_sound(emit_tetra(kThesis));
}

TEST(Tetrachiral, FiftyRandomValidSpecimensAreOneStrandWithoutCrossings) {
  std::mt19937 rng(20201);
  for (int i = 0; i < 50; ++i) {
    const auto given = chiral_testing::random_params(rng, &min_cell_for);
    SCOPED_TRACE(given.dump());
    chiral_testing::expect_sound(emit_tetra(given));
  }
}

TEST(Tetrachiral, NodeRingIsPassesTimesLayerHeightPlusNozzle) {
  const auto e = emit_tetra(kThesis);
  const double d = 0.5, h = 0.4;
  EXPECT_NEAR(e.toolpath.derived.at("node_radius_mm").get<double>(), 1.87 / 2 + h + d / 2, 1e-12);
  EXPECT_NEAR(e.toolpath.derived.at("node_ring_thickness_mm").get<double>(), 2 * h + d, 1e-12);
}

TEST(Tetrachiral, ThesisPorosityFormulaIsReportedBesideTheMeasuredOne) {
  const auto e = emit_tetra(kThesis);
  const double l = 10, d = 0.5, h = 0.4, r = 1.87 / 2 + h + d / 2, a = std::atan(2 * r / l);
  const double expected = 1 - (2 * l * d / std::cos(a) + M_PI * r * (3 * h + 2 * d)) / (l * l);
  EXPECT_NEAR(e.toolpath.derived.at("porosity_thesis").get<double>(), expected, 1e-12);
  const double measured = e.toolpath.derived.at("porosity").get<double>();
  EXPECT_GT(measured, 0.5);
  EXPECT_LT(measured, 0.95);
}

TEST(Tetrachiral, GripsAddTheirLengthAtBothEnds) {
  auto no_grip = kThesis;
  no_grip["grip"] = 0;
  const double with = emit_tetra(kThesis).toolpath.derived.at("size_mm")[1].get<double>();
  const double without = emit_tetra(no_grip).toolpath.derived.at("size_mm")[1].get<double>();
  EXPECT_NEAR(with - without, 2 * (10 + 0.5), 1e-9) << "tab plus a one-pitch gap at each end";
  chiral_testing::expect_sound(emit_tetra(no_grip));
}

slicer::Toolpath wrap_tetra(const nlohmann::json& given, double period_mm) {
  return find_generator("tetrachiral")
      ->generate_wrapped(slicer::resolve_params(tetrachiral_table(), given), period_mm);
}

// The sample: a tetrachiral sleeve with --wrap full on a 15 mm radius cylinder.
TEST(TetrachiralWrap, ThesisSleeveClosesRoundTheCylinderAsOneStrand) {
  const double period = 2 * M_PI * 15.0;  // 94.25 mm: 9.4 cells of 10 mm -> 10 of 9.42 mm
  const slicer::Toolpath t = wrap_tetra(kThesis, period);
  testing::expect_sound_wrap(t, period);
  EXPECT_EQ(t.derived.at("cells_around").get<int>(), 10);
  EXPECT_NEAR(t.derived.at("cell_mm").get<double>(), period / 10, 1e-12);
  EXPECT_EQ(t.derived.at("cells")[0].get<int>(), 10);
  EXPECT_NEAR(t.derived.at("size_mm")[0].get<double>(), period, 1e-9);
  const auto pieces = testing::seam_pieces(t.layers[0].strokes[0], period);
  EXPECT_GT(pieces.size(), 2u) << "the strand runs across the seam";
  // as long along y as the flat specimen with the adjusted cell and the same rows and grips
  auto flat = kThesis;
  flat["cell"] = period / 10;
  const auto flat_t =
      find_generator("tetrachiral")->generate(slicer::resolve_params(tetrachiral_table(), flat));
  EXPECT_NEAR(t.derived.at("size_mm")[1].get<double>(),
              flat_t.derived.at("size_mm")[1].get<double>(), 1e-6);
}

TEST(TetrachiralWrap, ThirtyRandomSleevesAreSoundOnTheCylinder) {
  chiral_testing::expect_random_sleeves("tetrachiral", &min_cell_for, 4, 2, 1101);
}

TEST(TetrachiralWrap, TooSmallACircumferenceNamesWrapAndTheLimit) {
  const double min_cell = min_cell_for(kThesis);
  try {
    wrap_tetra(kThesis, 4 * min_cell - 0.1);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("tetrachiral.wrap = full: "), std::string::npos) << m;
    EXPECT_NE(m.find("at least 4 cells around"), std::string::npos) << m;
    EXPECT_NE(m.find(slicer::short_number(min_cell) + " mm"), std::string::npos) << m;
  }
  EXPECT_NO_THROW(wrap_tetra(kThesis, 4 * min_cell + 1e-6));
  EXPECT_THROW(wrap_tetra(kThesis, 0.0), InputError);
  EXPECT_THROW(wrap_tetra(kThesis, 1e7), InputError) << "bounded work";
}

void expect_input_error(const nlohmann::json& given, const std::string& needle) {
  try {
    find_generator("tetrachiral")->generate(slicer::resolve_params(tetrachiral_table(), given));
    FAIL() << "expected InputError for " << given.dump();
  } catch (const InputError& ex) {
    EXPECT_NE(std::string(ex.what()).find(needle), std::string::npos) << ex.what();
  }
}

TEST(TetrachiralParams, CellTooSmallForTheNodeNamesTheLimit) {
  auto bad = kThesis;
  bad["cell"] = 4;
  const double limit = min_cell_for(kThesis);
  expect_input_error(bad, "tetrachiral.cell = 4: must be >= " + slicer::short_number(limit));
  auto ok = kThesis;
  ok["cell"] = limit;
  chiral_testing::expect_sound(emit_tetra(ok));
}

TEST(TetrachiralParams, EvenOrZeroPassesAndBadFactorsAreRejected) {
  auto even = kThesis;
  even["node-passes"] = 2;
  expect_input_error(even, "node-passes = 2: must be odd");
  auto zero = kThesis;
  zero["node-passes"] = 0;
  EXPECT_THROW(slicer::resolve_params(tetrachiral_table(), zero), InputError);
  auto factor = kThesis;
  factor["node-speed-factor"] = 0;
  EXPECT_THROW(slicer::resolve_params(tetrachiral_table(), factor), InputError);
  auto grip = kThesis;
  grip["grip"] = 0.5;
  expect_input_error(grip, "grip = 0.5: must be 0 or >= 2 * nozzle = 1");
}

TEST(TetrachiralParams, TooLargeForTheDeltaIsAnInputError) {
  auto huge = kThesis;
  huge["cols"] = 20;
  EXPECT_THROW(emit_tetra(huge), InputError);
}

}  // namespace
}  // namespace strand::patterns
