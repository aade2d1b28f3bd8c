// Graded, staggered and scheduled log-piles, measured on the written G-code read back: filament
// positions against the grade and the stagger, one strand per layer, no crossing, strand check.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "jobs/job_runner.h"
#include "machines/profile.h"
#include "patterns/registry.h"
#include "patterns/scaffold.h"
#include "postprocess/inspect/check.h"
#include "postprocess/inspect/gcode_parser.h"
#include "postprocess/plan/estimate.h"
#include "postprocess/plan/produce.h"
#include "slicer/input_error.h"
#include "slicer/units.h"
#include "tests/support/gcode_view.h"

namespace strand::patterns {
namespace {

struct Written {
  slicer::Toolpath toolpath;
  post::ParsedGcode parsed;
  std::string gcode;
};

Written write(const nlohmann::json& given) {
  const auto values = slicer::resolve_params(scaffold_table(), given);
  Written w;
  w.toolpath = find_generator("scaffold")->generate(values);
  const auto m = machines::load_profile("deltawasp-2040-clay");
  w.gcode = post::produce(w.toolpath, m, post::plan_options_from(w.toolpath, 0.01), "x.gcode").gcode;
  w.parsed = post::parse_gcode(w.gcode);
  return w;
}

// Offsets c = p . n of a layer's filaments running at `angle_deg` (n = (-sin, cos)), sorted;
// a filament is an infill move along that direction at least `min_mm` long.
std::vector<double> filament_offsets(const Written& w, int layer, double angle_deg, double min_mm) {
  const double a = slicer::deg_to_rad(angle_deg);
  const slicer::Vec2 u(std::cos(a), std::sin(a)), n(-std::sin(a), std::cos(a));
  std::vector<double> out;
  for (const auto& s : testing::deposit_segments(w.parsed.program)) {
    const slicer::Vec2 d = (s.b - s.a).head<2>();
    if (s.layer != layer || s.feature != slicer::Feature::Infill || d.norm() < min_mm) continue;
    if (std::abs(d.normalized().dot(u)) < 1 - 1e-4) continue;
    out.push_back(s.a.head<2>().dot(n));
  }
  std::sort(out.begin(), out.end());
  return out;
}

// Every layer: one strand, no crossing; and strand check passes on the file.
void expect_sound(const Written& w) {
  for (const auto& l : post::estimate(w.parsed.program).layers) EXPECT_EQ(l.strands, 1) << "layer " << l.layer;
  post::CheckOptions o;
  const auto m = machines::load_profile("deltawasp-2040-clay");
  o.machine = &m;
  const auto report = post::check_gcode(w.gcode, o);
  EXPECT_TRUE(report.ok()) << post::to_text(report);
}

const nlohmann::json kGradedX = {{"nozzle", 0.6}, {"gap", "0.8..1.6"}, {"grade", "x"}, {"size", "20x8"}, {"layers", 2}};

TEST(ScaffoldGraded, LinearGapAlongXMeasuredFromTheFileFollowsTheGrade) {
  const auto w = write(kGradedX);
  const double d = 0.6, length = 20.0;
  // Layer 1 (90 deg): filaments along y at x = -c; from the low edge, each gap is the grade
  // at its start.
  std::vector<double> x = filament_offsets(w, 1, 90, 8);
  for (double& v : x) v = -v;
  std::sort(x.begin(), x.end());
  ASSERT_GE(x.size(), 10u);
  const double low_edge = x.front() - d / 2;
  for (std::size_t i = 0; i + 1 < x.size(); ++i) {
    const double start = x[i] + d / 2 - low_edge;
    const double want = 0.8 + 0.8 * std::clamp(start / length, 0.0, 1.0);
    EXPECT_NEAR(x[i + 1] - x[i] - d, want, 0.01) << "gap " << i << " starting " << start << " mm in";
  }
  EXPECT_NEAR(x.back() - x.front() + d, w.toolpath.derived.at("footprint_mm")[0].get<double>(), 0.01);
  EXPECT_NEAR(x.back() + x.front(), 0.0, 0.01) << "centred";
  // Layer 0 (0 deg, parallel to the grade): the mean gap, 1.2 mm, everywhere.
  const auto y = filament_offsets(w, 0, 0, 15);
  for (std::size_t i = 0; i + 1 < y.size(); ++i) EXPECT_NEAR(y[i + 1] - y[i] - d, 1.2, 0.01);
  expect_sound(w);
}

TEST(ScaffoldGraded, ZonesAlongYEachKeepTheirGap) {
  const nlohmann::json given = {{"nozzle", 0.6}, {"gap", "0.8,1.2,1.6"}, {"grade", "y"}, {"size", "8x24"}, {"layers", 2}};
  const auto w = write(given);
  const auto y = filament_offsets(w, 0, 0, 8);  // 0 deg: along x, at y = c
  const double d = 0.6, low_edge = y.front() - d / 2;
  for (std::size_t i = 0; i + 1 < y.size(); ++i) {
    const double start = y[i] + d / 2 - low_edge;
    const double want = start < 8 ? 0.8 : start < 16 ? 1.2 : 1.6;
    EXPECT_NEAR(y[i + 1] - y[i] - d, want, 0.01) << "gap starting " << start << " mm in";
  }
  expect_sound(w);
}

TEST(ScaffoldGraded, ZonePorositiesRiseWithTheGapAndAddUpToTheWhole) {
  auto given = kGradedX;
  given["layers"] = 4;
  const auto t = write(given).toolpath;
  const auto& zones = t.derived.at("porosity_zones");
  ASSERT_EQ(zones.size(), 4u);
  const double width = t.derived.at("footprint_mm")[0].get<double>();
  EXPECT_LT(zones.front().at("porosity").get<double>() + 0.03, zones.back().at("porosity").get<double>());
  double solid = 0.0;
  for (const auto& z : zones) {
    const double p = z.at("porosity").get<double>();
    solid += (1 - p) * (z.at("to_mm").get<double>() - z.at("from_mm").get<double>());
  }
  EXPECT_NEAR(1 - solid / width, t.derived.at("porosity").get<double>(), 1e-9);
}

TEST(ScaffoldGraded, AlongZEachLayerTakesTheGapAtItsBottom) {
  const nlohmann::json given = {{"nozzle", 0.6}, {"gap", "0.8..1.6"}, {"grade", "z"}, {"size", "12x12"}, {"layers", 4}, {"angles", "0"}};
  const auto w = write(given);
  for (int k = 0; k < 4; ++k) {
    const auto y = filament_offsets(w, k, 0, 10);
    ASSERT_GE(y.size(), 2u);
    for (std::size_t i = 0; i + 1 < y.size(); ++i) EXPECT_NEAR(y[i + 1] - y[i] - 0.6, 0.8 + 0.8 * k / 4, 0.01) << "layer " << k;
  }
  expect_sound(w);
}

TEST(ScaffoldGraded, ObliqueGradedLayersStayOneStrandWithoutCrossing) {
  auto given = kGradedX;
  given["angles"] = "0,60,120";
  given["layers"] = 3;
  given["stagger"] = true;
  expect_sound(write(given));
}

void expect_same(const std::vector<double>& a, const std::vector<double>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], b[i], 0.01) << "filament " << i;
}

TEST(ScaffoldStagger, TriangularPileLaysTheIntendedFilaments) {
  const nlohmann::json given = {{"nozzle", 0.6}, {"gap", 1.2}, {"size", "20x20"}, {"layers", 6}, {"angles", "0,60,120"}};
  const double pitch = 1.8;
  auto staggered = given;
  staggered["stagger"] = true;
  const auto plain = write(given), shifted = write(staggered);
  for (int k = 0; k < 3; ++k) {
    const double angle = 60.0 * k;
    const auto c = filament_offsets(plain, k, angle, 0.05);
    ASSERT_GE(c.size(), 5u) << "layer " << k;
    // Centred on the part, a pitch apart.
    EXPECT_NEAR(c.front() + c.back(), 0.0, 0.01) << "layer " << k;
    for (std::size_t i = 0; i + 1 < c.size(); ++i) EXPECT_NEAR(c[i + 1] - c[i], pitch, 0.01);
    // The same direction next time: unchanged without --stagger, half a pitch over with it.
    expect_same(filament_offsets(plain, k + 3, angle, 0.05), c);
    expect_same(filament_offsets(shifted, k, angle, 0.05), c);
    const auto s = filament_offsets(shifted, k + 3, angle, 0.05);
    ASSERT_EQ(s.size() + 1, c.size()) << "layer " << k + 3;
    for (std::size_t i = 0; i < s.size(); ++i) EXPECT_NEAR(s[i], c[i] + pitch / 2, 0.01) << "layer " << k + 3;
  }
  expect_sound(plain);
  expect_sound(shifted);
}

TEST(ScaffoldStagger, PorosityIsTheLaidVolumeOverTheBox) {
  const nlohmann::json given = {{"nozzle", 0.84}, {"gap", 1.6}, {"size", "20x20"}, {"layers", 4}, {"stagger", "on"}};
  const auto t = write(given).toolpath;
  // 0/90 on a square of N filaments: layers 2 and 3 lay N - 1 of the same length.
  const double d = 0.84, h = 0.88 * d, side = t.derived.at("footprint_mm")[0].get<double>();
  const int n = static_cast<int>(std::lround((side - d) / 2.44)) + 1;
  const double laid = (2 * n + 2 * (n - 1)) * side * slicer::bead_area_mm2(d, h);
  EXPECT_NEAR(t.derived.at("porosity").get<double>(), 1 - laid / (side * side * 4 * h), 1e-9);
  EXPECT_EQ(t.derived.at("filaments_per_layer"), (nlohmann::json{n, n, n - 1, n - 1}));
}

// A job file with a schedule, run as `strand job` runs it.
post::Produced run_scheduled(const nlohmann::json& schedule) {
  const nlohmann::json job = {{"generator", "scaffold"},
                              {"params", {{"nozzle", 0.6}, {"gap", 1.0}, {"size", "12x12"}, {"layers", 6}}},
                              {"schedule", schedule}};
  const jobs::JobSpec spec = jobs::job_spec_from_json(job, "job");
  auto settings = spec.settings;
  settings.keep_program = true;
  return jobs::produce_job(*spec.generator, spec.params, settings);
}

TEST(ScaffoldSchedule, LayerRangesTakeTheirSpeedGapAngleAndFlow) {
  const auto produced = run_scheduled({{{"layers", "0-1"}, {"speed", "5mm/s"}, {"gap", 1.4}},
                                       {{"layers", "4-5"}, {"angle", 45}, {"flow", 1.2}}});
  const auto parsed = post::parse_gcode(produced.gcode);
  Written w{{}, parsed, produced.gcode};
  // Layers 0-1: 300 mm/min, gap 1.4; layers 2-3 as the parameters; 4-5 at 45 deg.
  for (const auto& mv : parsed.program.moves) {
    if (mv.kind != slicer::MoveKind::Deposit || mv.feature != slicer::Feature::Infill) continue;
    EXPECT_NEAR(mv.feed_mm_per_min, mv.layer < 2 ? 300.0 : 250.0, 1e-9) << "layer " << mv.layer;
  }
  const auto gap14 = filament_offsets(w, 0, 0, 10);
  for (std::size_t i = 0; i + 1 < gap14.size(); ++i) EXPECT_NEAR(gap14[i + 1] - gap14[i] - 0.6, 1.4, 0.01);
  const auto gap10 = filament_offsets(w, 2, 0, 10);
  for (std::size_t i = 0; i + 1 < gap10.size(); ++i) EXPECT_NEAR(gap10[i + 1] - gap10[i] - 0.6, 1.0, 0.01);
  EXPECT_GE(filament_offsets(w, 4, 45, 3).size(), 5u);
  EXPECT_TRUE(filament_offsets(w, 4, 0, 3).empty());
  // Flow 1.2: the ink per mm of layers 4-5 is 1.2 times that of the others.
  const auto& layers = produced.report.at("layers");
  const double per_mm_2 = layers[2].at("volume_mm3").get<double>() / layers[2].at("deposit_length_mm").get<double>();
  const double per_mm_4 = layers[4].at("volume_mm3").get<double>() / layers[4].at("deposit_length_mm").get<double>();
  EXPECT_NEAR(per_mm_4 / per_mm_2, 1.2, 1e-3);
  EXPECT_EQ(produced.report.at("derived").at("porosity_by_schedule").size(), 2u);
  expect_sound(w);
}

TEST(ScaffoldSchedule, BadEntriesAreOneLineNamingTheRangeAndKey) {
  const std::vector<std::pair<nlohmann::json, std::string>> cases = {
      {{{{"layers", "0-4"}, {"speed", -5}}}, "scaffold.schedule[0-4].speed = -5: must be in (0, 1e+05] (mm/min)"},
      {{{{"layers", "2-9"}, {"gap", 1}}}, "scaffold.schedule[0].layers = 2-9: must be FIRST-LAST with 0 <= FIRST <= LAST <= 5"},
      {{{{"layers", "0-3"}, {"gap", 1}}, {{"layers", "3-4"}, {"gap", 2}}}, "scaffold.schedule[3-4].layers: overlaps layers 0-3"},
      {{{{"layers", "1"}, {"pressure", 2}}}, "scaffold.schedule[1].pressure: unknown parameter"},
      {{{{"layers", "1"}, {"flow", 0.3}}}, "scaffold.schedule[1-1].flow = 0.3: gives beads"},
  };
  for (const auto& [schedule, message] : cases) {
    try {
      run_scheduled(schedule);
      ADD_FAILURE() << "accepted " << schedule.dump();
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what() << "\nwanted: " << message;
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
  }
}

}  // namespace
}  // namespace strand::patterns
