// Scaffold properties checked on the emitted G-code parsed back, not on internal state.
#include "patterns/scaffold.h"
#include "patterns/registry.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

#include "machines/profile.h"
#include "postprocess/inspect/crossings.h"
#include "postprocess/plan/estimate.h"
#include "postprocess/inspect/gcode_parser.h"
#include "postprocess/plan/produce.h"
#include "slicer/input_error.h"
#include "slicer/units.h"
#include "tests/support/gcode_view.h"
#include "tests/support/wrap_checks.h"

namespace strand::patterns {
namespace {

struct Emitted {
  slicer::Toolpath toolpath;
  post::ParsedGcode parsed;
  std::string gcode;
};

Emitted emit(const nlohmann::json& given, const std::string& machine = "deltawasp-2040-clay") {
  const auto values = slicer::resolve_params(scaffold_table(), given);
  Emitted e;
  e.toolpath = find_generator("scaffold")->generate(values);
  const auto m = machines::load_profile(machine);
  e.gcode = post::produce(e.toolpath, m, post::plan_options_from(e.toolpath, 0.01), "x.gcode").gcode;
  e.parsed = post::parse_gcode(e.gcode);
  return e;
}

const nlohmann::json kThesis = {{"nozzle", 0.84}, {"gap", 1.6}, {"size", "36x36"}, {"height", 13}};

TEST(Scaffold, OneStrandPerLayer) {
  const auto e = emit(kThesis);
  const auto est = post::estimate(e.parsed.program);
  ASSERT_FALSE(est.layers.empty());
  for (const auto& l : est.layers) EXPECT_EQ(l.strands, 1) << "layer " << l.layer;
}

TEST(Scaffold, NoSelfCrossingInsideALayer) {
  for (const char* angles : {"0,90", "0,60,120", "45,135", "30"}) {
    SCOPED_TRACE(angles);
    auto given = kThesis;
    given["angles"] = angles;
    const auto e = emit(given);
    const auto c = post::find_contacts(e.parsed.program, 0.01, 1e-3);
    EXPECT_TRUE(c.crossings.empty()) << c.crossings.size() << " crossings, first at "
                                     << (c.crossings.empty() ? slicer::Vec2(0, 0) : c.crossings[0].at_mm).transpose();
  }
}

// Direction of each long infill move, as an angle in [0, 180).
std::set<long> long_move_angles(const Emitted& e, int layer, double min_len) {
  std::set<long> out;
  for (const auto& s : testing::deposit_segments(e.parsed.program)) {
    if (s.layer != layer || s.feature != slicer::Feature::Infill) continue;
    const slicer::Vec3 d = s.b - s.a;
    if (d.head<2>().norm() < min_len) continue;
    double a = slicer::rad_to_deg(std::atan2(d.y(), d.x()));
    a = std::fmod(a + 360.0, 180.0);
    out.insert(std::lround(a) % 180);
  }
  return out;
}

TEST(Scaffold, DirectionsFollowAngles) {
  auto given = kThesis;
  given["angles"] = "0,60,120";
  const auto e = emit(given);
  EXPECT_EQ(long_move_angles(e, 0, 20), std::set<long>{0});
  EXPECT_EQ(long_move_angles(e, 1, 20), std::set<long>{60});
  EXPECT_EQ(long_move_angles(e, 2, 20), std::set<long>{120});
  EXPECT_EQ(long_move_angles(e, 3, 20), std::set<long>{0});
}

TEST(Scaffold, FootprintMatchesReportWithinTolerance) {
  const auto e = emit(kThesis);
  const double d = 0.84;
  double xmin = 1e9, xmax = -1e9, ymin = 1e9, ymax = -1e9;
  // Filament centre lines: long moves along y (layer 1) give x, along x (layer 0) give y.
  for (const auto& s : testing::deposit_segments(e.parsed.program)) {
    const slicer::Vec3 dv = s.b - s.a;
    if (s.feature != slicer::Feature::Infill || dv.head<2>().norm() < 20) continue;
    if (std::abs(dv.x()) < 1e-9) xmin = std::min(xmin, s.a.x()), xmax = std::max(xmax, s.a.x());
    if (std::abs(dv.y()) < 1e-9) ymin = std::min(ymin, s.a.y()), ymax = std::max(ymax, s.a.y());
  }
  const auto& fp = e.toolpath.derived.at("footprint_mm");
  EXPECT_NEAR(xmax - xmin + d, fp[0].get<double>(), 0.01);
  EXPECT_NEAR(ymax - ymin + d, fp[1].get<double>(), 0.01);
  EXPECT_NEAR((xmax + xmin) / 2, 0.0, 0.01) << "centred on the delta's axis";
  EXPECT_NEAR(fp[0].get<double>(), 35.0, 1e-9) << "36 mm rounds to 15 filaments at 2.44 mm pitch";
}

TEST(Scaffold, UTurnsLieOutsideTheFootprint) {
  const auto e = emit(kThesis);
  const double half = e.toolpath.derived.at("footprint_mm")[0].get<double>() / 2;
  for (const auto& s : testing::deposit_segments(e.parsed.program)) {
    const slicer::Vec3 dv = s.b - s.a;
    if (s.feature != slicer::Feature::Infill || dv.head<2>().norm() > 20) continue;
    // short infill moves are the U-turn connectors: both ends outside the footprint
    EXPECT_GT(std::max(std::abs(s.a.x()), std::abs(s.a.y())), half);
    EXPECT_GT(std::max(std::abs(s.b.x()), std::abs(s.b.y())), half);
  }
}

TEST(Scaffold, LayerCountFromHeightOrLayers) {
  auto by_layers = kThesis;
  by_layers.erase("height");
  by_layers["layers"] = 7;
  EXPECT_EQ(emit(by_layers).parsed.program.layers.size(), 7u);
  // 13 mm / (0.88 * 0.84 mm) = 17.6 -> 18 layers
  EXPECT_EQ(emit(kThesis).parsed.program.layers.size(), 18u);
}

TEST(Scaffold, EveryMoveInsideTheDeltaCylinder) {
  auto big = kThesis;
  big["size"] = "130x130";
  const auto e = emit(big);
  for (const auto& mv : e.parsed.program.moves) {
    if (mv.kind == slicer::MoveKind::Raw || mv.kind == slicer::MoveKind::Dwell) continue;
    EXPECT_LE(std::hypot(mv.end_mm.x(), mv.end_mm.y()), 100.0);
    EXPECT_GE(mv.end_mm.z(), 0.0);
  }
}

TEST(Scaffold, TooLargeForTheDeltaIsAnErrorNamingTheRadius) {
  auto huge = kThesis;
  huge["size"] = "150x150";
  try {
    emit(huge);
    FAIL() << "expected InputError";
  } catch (const InputError& ex) {
    EXPECT_NE(std::string(ex.what()).find("radius"), std::string::npos) << ex.what();
  }
}

TEST(Scaffold, CartesianMachineCentresOnItsBedAndUsesVolumetricE) {
  const auto e = emit(kThesis, "marlin-xyz-200");
  double e_total = 0;
  for (const auto& mv : e.parsed.program.moves) e_total += mv.kind == slicer::MoveKind::Deposit ? 1 : 0;
  EXPECT_GT(e_total, 0);
  EXPECT_TRUE(e.parsed.has_e);
  const auto box = slicer::bounds(e.toolpath);
  EXPECT_LT(box.first.x(), 0) << "the toolpath itself stays part-centred";
  for (const auto& mv : e.parsed.program.moves) {
    if (mv.kind == slicer::MoveKind::Deposit) {
      EXPECT_GT(mv.end_mm.x(), 50);
    }
  }
}

TEST(Scaffold, PorosityMatchesLogPileFormula) {
  // For 0/90 with N filaments over depth D: P = 1 - N * A / (D * h).
  const auto e = emit(kThesis);
  const double d = 0.84, h = 0.88 * d, D = 35.0, N = 15;
  const double A = slicer::bead_area_mm2(d, h);
  EXPECT_NEAR(e.toolpath.derived.at("porosity").get<double>(), 1 - N * A / (D * h), 1e-9);
}

TEST(ScaffoldParams, LayerHeightOutsideHalfToOneNozzleIsRejected) {
  auto bad = kThesis;
  bad["layer-height"] = 0.3;
  try {
    scaffold_params_from(slicer::resolve_params(scaffold_table(), bad));
    FAIL();
  } catch (const InputError& ex) {
    EXPECT_NE(std::string(ex.what()).find("[0.42, 0.84]"), std::string::npos) << ex.what();
  }
}

slicer::Toolpath wrap_scaffold(const nlohmann::json& given, double period_mm) {
  return find_generator("scaffold")->generate_wrapped(slicer::resolve_params(scaffold_table(), given),
                                                      period_mm);
}

// Each layer starts where the previous one ended, on the cylinder (x modulo the period).
void expect_layers_join(const slicer::Toolpath& t, double period_mm) {
  for (std::size_t k = 1; k < t.layers.size(); ++k) {
    const slicer::Vec2 d = t.layers[k].strokes[0].start_mm - t.layers[k - 1].strokes[0].end_mm();
    EXPECT_NEAR(std::remainder(d.x(), period_mm), 0.0, 1e-9) << "layer " << k;
    EXPECT_NEAR(d.y(), 0.0, 1e-9) << "layer " << k;
  }
}

TEST(ScaffoldWrap, ThesisScaffoldAsASleeve) {
  const double period = 2 * M_PI * 20;  // 125.66 mm: 51.5 pitches of 2.44 -> 52 lines
  const auto t = wrap_scaffold(kThesis, period);
  testing::expect_sound_wrap(t, period);
  expect_layers_join(t, period);
  EXPECT_EQ(t.derived.at("axial_lines").get<int>(), 52);
  const double half = t.derived.at("footprint_mm")[1].get<double>() / 2 + 0.84;  // + overhang
  // layer 1 (90 deg): 52 lines along the axis from end to end, U-turns beyond the ends
  int axial = 0;
  for (const auto& [a, b] : testing::flat_segments(t.layers[1].strokes[0], 0.01)) {
    if (std::abs(a.x() - b.x()) < 1e-12 && std::abs(std::abs(b.y() - a.y()) - 2 * half) < 1e-9) ++axial;
  }
  EXPECT_EQ(axial, 52);
  // layer 0 (0 deg): one helix; every turn a pitch (2.44 mm) beside the last
  const auto& helix = t.layers[0].strokes[0];
  const int turns = t.derived.at("helix_turns").get<int>();
  EXPECT_NEAR(helix.end_mm().x() - helix.start_mm.x(), turns * period, 1e-9);
  EXPECT_NEAR(helix.end_mm().y() - helix.start_mm.y(), turns * 2.44, 1e-9);
  EXPECT_EQ(turns + 1, t.derived.at("filaments_per_layer")[0].get<int>());
}

TEST(ScaffoldWrap, FortyRandomSleevesAreSoundAndEachLayerStartsWhereTheLastEnded) {
  std::mt19937 rng(1103);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const std::vector<std::vector<double>> angle_sets = {{0, 90}, {90, 0}, {0}, {90}, {90, 90, 0}, {-90, 180}};
  for (int i = 0; i < 40; ++i) {
    const double d = 0.2 + 0.8 * unit(rng), pitch = d * (1.0 + 3 * unit(rng));
    const nlohmann::json given = {{"nozzle", d},
                                  {"pitch", pitch},
                                  {"size", {10.0, 3 * d + 30 * unit(rng)}},
                                  {"layers", 1 + static_cast<int>(rng() % 5)},
                                  {"angles", angle_sets[rng() % angle_sets.size()]}};
    const double period = pitch * (3 + 40 * unit(rng));
    SCOPED_TRACE(given.dump() + " period " + std::to_string(period));
    const auto t = wrap_scaffold(given, period);
    testing::expect_sound_wrap(t, period);
    expect_layers_join(t, period);
    EXPECT_GE(t.derived.at("axial_line_pitch_mm").get<double>(), d - 1e-12);
  }
}

TEST(ScaffoldWrap, ObliqueAnglesAndTooSmallACircumferenceAreInputErrors) {
  auto oblique = kThesis;
  oblique["angles"] = {0, 45};
  try {
    wrap_scaffold(oblique, 100);
    FAIL() << "accepted 45 deg";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("scaffold.angles = 0,45: with --wrap full each angle must be 0"),
              std::string::npos) << e.what();
  }
  try {
    wrap_scaffold(kThesis, 2.0);
    FAIL() << "accepted a 2 mm circumference";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("scaffold.wrap = full: a 2 mm circumference is too small: "
                                         "at least 3 cells around (lines along the axis) of at least "
                                         "0.84 mm"),
              std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace strand::patterns
