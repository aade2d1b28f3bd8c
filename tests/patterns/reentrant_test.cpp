// Re-entrant honeycomb checked on the emitted G-code parsed back: no crossing, one strand per
// layer, the size of the report, and the ribs of a bow-tie honeycomb at the given angle.
#include "patterns/reentrant.h"
#include "patterns/registry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

#include "machines/profile.h"
#include "postprocess/inspect/crossings.h"
#include "postprocess/plan/estimate.h"
#include "postprocess/inspect/gcode_parser.h"
#include "postprocess/plan/produce.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"
#include "slicer/units.h"
#include "tests/support/gcode_view.h"
#include "tests/support/lattice_checks.h"
#include "tests/support/wrap_checks.h"

namespace strand::patterns {
namespace {

using Emitted = testing::EmittedPart;

Emitted emit(const nlohmann::json& given) {
  return testing::emit_on_delta(reentrant_table(), find_generator("reentrant")->generate, given);
}

const nlohmann::json kSample = {{"nozzle", 0.6},  {"cell-width", 8.0}, {"cell-height", 7.0},
                                {"angle", 20},    {"rows", 4},         {"cols", 4},
                                {"layers", 3}};

void expect_sound(const Emitted& e, const std::string& what) { testing::expect_sound_lattice(e, what); }

TEST(Reentrant, FiftyRandomValidHoneycombsHaveNoCrossingAndOneStrandPerLayer) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> nozzle(0.4, 0.84), width_in_d(4.0, 14.0), aspect(0.5, 1.6),
      angle_share(0.05, 1.0);
  std::uniform_int_distribution<int> cols(1, 6), half_rows(1, 4), layers(1, 3);
  for (int n = 0; n < 50; ++n) {
    const double d = nozzle(rng);
    const double w = width_in_d(rng) * d;
    const double h = std::max(aspect(rng) * w, 1.2 * d);
    const double max_angle = slicer::rad_to_deg(std::atan((h - d) / w));
    const nlohmann::json given = {{"nozzle", d},   {"cell-width", w},           {"cell-height", h},
                                  {"angle", angle_share(rng) * max_angle},      {"rows", 2 * half_rows(rng)},
                                  {"cols", cols(rng)}, {"layers", layers(rng)}};
    expect_sound(emit(given), given.dump());
  }
}

slicer::Toolpath wrap_reentrant(const nlohmann::json& given, double period_mm) {
  return find_generator("reentrant")
      ->generate_wrapped(slicer::resolve_params(reentrant_table(), given), period_mm);
}

TEST(ReentrantWrap, SampleHoneycombClosesRoundACylinderAsOneStrand) {
  const double period = 2 * M_PI * 10;  // 62.83 mm: 7.85 cells of 8 mm -> 8 of 7.85 mm
  const auto t = wrap_reentrant(kSample, period);
  testing::expect_sound_wrap(t, period);
  EXPECT_EQ(t.derived.at("cells_around").get<int>(), 8);
  EXPECT_EQ(t.derived.at("bands").get<int>(), 16);
  EXPECT_NEAR(t.derived.at("cell_width_mm").get<double>(), period / 8, 1e-12);
  const auto& s = t.layers[0].strokes[0];
  EXPECT_NEAR(s.end_mm().x() - s.start_mm.x(), period, 1e-9) << "closed once round the cylinder";
  EXPECT_NEAR(s.end_mm().y(), s.start_mm.y(), 1e-9);
  EXPECT_GE(testing::wrapped_min_gap(t.layers[0], period), 0.6 - 2e-3);
  const auto& fp = t.derived.at("footprint_mm");
  EXPECT_NEAR(fp[0].get<double>(), period, 1e-12);
}

TEST(ReentrantWrap, ThirtyRandomSleevesAreSoundAndKeepANozzleApart) {
  std::mt19937 rng(1105);
  std::uniform_real_distribution<double> nozzle(0.4, 0.84), width_in_d(4.0, 14.0), aspect(0.5, 1.6),
      angle_share(0.05, 0.9), around(2.0, 12.0);
  for (int n = 0; n < 30; ++n) {
    const double d = nozzle(rng);
    const double w = width_in_d(rng) * d;
    const double h = std::max(aspect(rng) * w, 1.2 * d);
    const double max_angle = slicer::rad_to_deg(std::atan((h - d) / w));
    const nlohmann::json given = {{"nozzle", d},     {"cell-width", w},
                                  {"cell-height", h}, {"angle", angle_share(rng) * max_angle},
                                  {"rows", 2 * (1 + static_cast<int>(rng() % 3))}, {"layers", 2}};
    const double period = around(rng) * w;
    SCOPED_TRACE(given.dump() + " period " + std::to_string(period));
    slicer::Toolpath t;
    try {
      t = wrap_reentrant(given, period);
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("reentrant.wrap = full: "), std::string::npos);
      continue;
    }
    testing::expect_sound_wrap(t, period);
    EXPECT_GE(testing::wrapped_min_gap(t.layers[0], period), d - 2e-3);
  }
}

TEST(ReentrantWrap, TooSmallACircumferenceNamesWrapAndTheLimit) {
  try {
    wrap_reentrant(kSample, 2 * 4 * 0.6 - 0.1);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("reentrant.wrap = full: a 4.7 mm circumference is too "
                                         "small: at least 2 cells around"),
              std::string::npos) << e.what();
  }
}

TEST(Reentrant, RibsAreABowTieHoneycombAtTheAngle) {
  const auto e = emit(kSample);
  const int rows = 4, bands = 8;
  int vertical = 0, inclined = 0;
  std::set<long> vertical_x_um;  // x of the vertical passes, in micrometres
  for (const auto& s : testing::deposit_segments(e.parsed.program)) {
    if (s.layer != 0) continue;
    ASSERT_EQ(s.feature, slicer::Feature::Ligament);
    const slicer::Vec3 dv = s.b - s.a;
    if (std::abs(dv.x()) < 1e-9) {
      ++vertical;
      vertical_x_um.insert(std::lround(s.a.x() * 1000));
      continue;
    }
    ++inclined;
    const double a = slicer::rad_to_deg(std::atan(std::abs(dv.y() / dv.x())));
    EXPECT_NEAR(a, 20.0, 0.1) << "inclined rib at " << a << " deg";
  }
  // Every band climbs each row once and crosses each of the rows + 1 row boundaries once.
  EXPECT_EQ(vertical, bands * rows);
  EXPECT_EQ(inclined, bands * (rows + 1));
  // 9 rib lines, W / 2 = 4 mm apart: the 7 interior ones carry two passes d apart.
  EXPECT_EQ(vertical_x_um.size(), 2u + 2u * 7u);
  for (long x : vertical_x_um) {
    const double off = std::remainder(x / 1000.0, 4.0);
    EXPECT_TRUE(std::abs(off) < 1e-3 || std::abs(std::abs(off) - 0.3) < 2e-3) << x;
  }
}

TEST(Reentrant, TipsPointIntoTheCells) {
  // Re-entrant: the row pitch is shorter than the vertical rib by the tip depth.
  const auto e = emit(kSample);
  const double delta = 4.0 * std::tan(slicer::deg_to_rad(20.0));
  EXPECT_NEAR(e.toolpath.derived.at("tip_depth_mm").get<double>(), delta, 1e-12);
  EXPECT_NEAR(e.toolpath.derived.at("row_pitch_mm").get<double>(), 7.0 - delta, 1e-12);
  const double lift = 0.3 * std::tan(slicer::deg_to_rad(20.0));  // clipped lower ends of row 0
  EXPECT_NEAR(e.toolpath.derived.at("footprint_mm")[1].get<double>(), 3 * (7.0 - delta) + 7.0 - lift + 0.6, 1e-9);
  EXPECT_NEAR(e.toolpath.derived.at("footprint_mm")[0].get<double>(), 4 * 8.0 + 0.6, 1e-9);
}

TEST(Reentrant, LayersAlternateDirectionSoEachStartsWhereThePreviousEnded) {
  const auto& layers = emit(kSample).toolpath.layers;
  ASSERT_EQ(layers.size(), 3u);
  EXPECT_LT((layers[1].strokes[0].start_mm - layers[0].strokes[0].end_mm()).norm(), 1e-9);
  EXPECT_LT((layers[2].strokes[0].start_mm - layers[1].strokes[0].end_mm()).norm(), 1e-9);
}

TEST(Reentrant, PorosityFromDepositedLength) {
  const auto e = emit(kSample);
  const auto est = post::estimate(e.parsed.program);
  const auto& d = e.toolpath.derived;
  EXPECT_NEAR(d.at("filament_length_mm").get<double>(), est.deposit_length_mm, 0.05);
  const double box = d.at("footprint_mm")[0].get<double>() * d.at("footprint_mm")[1].get<double>() *
                     d.at("height_mm").get<double>();
  const double bead = slicer::bead_area_mm2(0.6, 0.8 * 0.6);
  EXPECT_NEAR(d.at("porosity").get<double>(), 1 - est.deposit_length_mm * bead / box, 1e-4);
}

TEST(Reentrant, SampleJobHasNoCrossingAndOneStrandPerLayer) {
  const auto job = nlohmann::json::parse(slicer::read_file(STRAND_SOURCE_DIR "/samples/reentrant.json"));
  ASSERT_EQ(job.at("generator"), "reentrant");
  ASSERT_EQ(job.at("machine"), "deltawasp-2040-clay");
  nlohmann::json given = job.at("params");
  const auto e = emit(given);
  expect_sound(e, "samples/reentrant.json");
  EXPECT_TRUE(post::find_contacts(e.parsed.program, 0.01, 1e-3).touches.empty()) << "passes stay a nozzle apart";
}

std::string error_of(const nlohmann::json& given) {
  return testing::input_error_of(reentrant_table(), find_generator("reentrant")->generate, given);
}

TEST(ReentrantParams, OddRowsAreRejected) {
  auto bad = kSample;
  bad["rows"] = 3;
  EXPECT_NE(error_of(bad).find("reentrant.rows = 3: must be even"), std::string::npos) << error_of(bad);
}

TEST(ReentrantParams, AngleThatClosesTheTipsNamesTheLimit) {
  auto bad = kSample;
  bad["angle"] = 40;  // limit atan((7 - 0.6) / 8) = 38.6598 deg
  const std::string msg = error_of(bad);
  EXPECT_NE(msg.find("reentrant.angle = 40: must be in (0, 38.6598]"), std::string::npos) << msg;
  auto ok = kSample;
  ok["angle"] = 38.6;
  EXPECT_EQ(error_of(ok), "");
  bad["angle"] = 0;
  EXPECT_NE(error_of(bad).find("(0, 90)"), std::string::npos) << error_of(bad);
}

TEST(ReentrantParams, CellTooNarrowForTheNozzleNamesTheLimit) {
  auto bad = kSample;
  bad["cell-width"] = 2.3;  // 4 * 0.6 = 2.4
  const std::string msg = error_of(bad);
  EXPECT_NE(msg.find("reentrant.cell-width = 2.3: must be >= 4 * nozzle = 2.4"), std::string::npos) << msg;
}

TEST(ReentrantParams, TooLargeForTheDeltaNamesTheRadius) {
  auto big = kSample;
  big["cols"] = 40;
  EXPECT_NE(error_of(big).find("radius"), std::string::npos) << error_of(big);
}

}  // namespace
}  // namespace strand::patterns
