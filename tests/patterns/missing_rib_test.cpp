// Missing-rib lattice checked on the emitted G-code parsed back: no crossing, one strand per
// layer, the size of the report, and the ribs of the intended lattice.
#include "patterns/missing_rib.h"
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
  return testing::emit_on_delta(missing_rib_table(), find_generator("missing-rib")->generate, given);
}

const nlohmann::json kSample = {{"nozzle", 0.6}, {"rib", 5.0}, {"angle", 20}, {"rows", 4}, {"cols", 5}, {"layers", 3}};

void expect_sound(const Emitted& e, const std::string& what) { testing::expect_sound_lattice(e, what); }

TEST(MissingRib, FiftyRandomValidLatticesHaveNoCrossingAndOneStrandPerLayer) {
  std::mt19937 rng(20240603);
  std::uniform_real_distribution<double> nozzle(0.4, 0.84), angle(1.0, 40.0), stretch(1.0, 1.8);
  std::uniform_int_distribution<int> cells(1, 6), layers(1, 3);
  for (int n = 0; n < 50; ++n) {
    const double d = nozzle(rng), a = angle(rng);
    const double t = slicer::deg_to_rad(a);
    const double limit = std::max(d / (std::cos(t) - std::sin(t)), d / std::cos(t) + d / std::sqrt(2.0));
    const double rib = stretch(rng) * limit + 1e-9;
    const nlohmann::json given = {{"nozzle", d}, {"rib", rib}, {"angle", a}, {"rows", cells(rng)},
                                  {"cols", cells(rng)}, {"layers", layers(rng)}};
    expect_sound(emit(given), given.dump());
  }
}

TEST(MissingRib, RibsAreTheRotatedNodeLattice) {
  const auto e = emit(kSample);
  const int rows = 4, cols = 5;
  const double rib = 5.0, theta = 20.0;
  const double d = 0.6, cut = d / std::sqrt(2.0);  // corner cut at each node, along each rib
  int ribs = 0, frame = 0, node_cuts = 0;
  std::set<long> tilt_signs;  // +1 / -1: rib leans ccw or cw from its nearest axis
  for (const auto& s : testing::deposit_segments(e.parsed.program)) {
    if (s.layer != 0) continue;
    const slicer::Vec3 dv = s.b - s.a;
    if (s.feature == slicer::Feature::Frame) {
      ++frame;
      EXPECT_TRUE(std::abs(dv.x()) < 1e-9 || std::abs(dv.y()) < 1e-9) << "frame runs along the axes";
      continue;
    }
    if (s.feature == slicer::Feature::Node) {
      ++node_cuts;
      EXPECT_NEAR(dv.head<2>().norm(), d, 2e-3) << "passes at a node stay one nozzle apart";
      continue;
    }
    ASSERT_EQ(s.feature, slicer::Feature::Ligament);
    ++ribs;
    EXPECT_NEAR(dv.head<2>().norm(), rib - cut, 2e-3) << "every rib has one end on a node";
    const double a = slicer::rad_to_deg(std::atan2(dv.y(), dv.x()));
    const double off_axis = std::remainder(a, 90.0);  // in [-45, 45]
    EXPECT_NEAR(std::abs(off_axis), theta, 0.05) << "rib at " << a << " deg";
    tilt_signs.insert(off_axis > 0 ? 1 : -1);
  }
  // Two ribs per neighbour pair (through the bend) plus one outward rib per boundary side of
  // each boundary node.
  const int expected = 2 * (rows + 1) * cols + 2 * (cols + 1) * rows + 2 * (rows + 1) + 2 * (cols + 1);
  EXPECT_EQ(ribs, expected);
  EXPECT_EQ(e.toolpath.derived.at("ribs_per_layer").get<int>(), expected);
  EXPECT_GT(frame, 0);
  EXPECT_EQ(node_cuts, 2 * (rows + 1) * (cols + 1)) << "two passes turn at every node";
  EXPECT_EQ(tilt_signs, (std::set<long>{-1, 1})) << "nodes alternate between +theta and -theta";
}

TEST(MissingRib, LargeLatticeIsStillOneClosedStrand) {
  MissingRibParams p;
  p.nozzle_mm = 0.5;
  p.rib_mm = 1.5;
  p.rows = 40;
  p.cols = 55;
  p.layers = 1;
  p.layer_height_mm = 0.4;
  const auto t = generate_missing_rib(p);
  ASSERT_EQ(t.layers[0].strokes.size(), 1u) << "circuits merged at nodes into one";
  const auto& s = t.layers[0].strokes[0];
  EXPECT_LT((s.end_mm() - s.start_mm).norm(), 1e-9) << "closed";
  int ribs = 0, cuts = 0;
  for (const auto& seg : s.segments) {
    ribs += seg.feature == slicer::Feature::Ligament;
    cuts += seg.feature == slicer::Feature::Node;
  }
  EXPECT_EQ(ribs, t.derived.at("ribs_per_layer").get<int>()) << "every rib once";
  EXPECT_EQ(cuts, 2 * 41 * 56) << "two passes turn at every node";
}

TEST(MissingRib, PitchAndSizeFollowFromRibAndAngle) {
  const auto e = emit(kSample);
  const double p = 2 * 5.0 * std::cos(slicer::deg_to_rad(20.0));
  EXPECT_NEAR(e.toolpath.derived.at("pitch_mm").get<double>(), p, 1e-12);
  EXPECT_NEAR(e.toolpath.derived.at("footprint_mm")[0].get<double>(), 6 * p + 0.6, 1e-9);
  EXPECT_NEAR(e.toolpath.derived.at("footprint_mm")[1].get<double>(), 5 * p + 0.6, 1e-9);
}

TEST(MissingRib, PorosityFromDepositedLength) {
  const auto e = emit(kSample);
  const auto est = post::estimate(e.parsed.program);
  const auto& d = e.toolpath.derived;
  EXPECT_NEAR(d.at("filament_length_mm").get<double>(), est.deposit_length_mm, 0.05);
  const double box = d.at("footprint_mm")[0].get<double>() * d.at("footprint_mm")[1].get<double>() *
                     d.at("height_mm").get<double>();
  const double bead = slicer::bead_area_mm2(0.6, 0.8 * 0.6);
  EXPECT_NEAR(d.at("porosity").get<double>(), 1 - est.deposit_length_mm * bead / box, 1e-4);
  EXPECT_GT(d.at("porosity").get<double>(), 0.0);
  EXPECT_LT(d.at("porosity").get<double>(), 1.0);
}

TEST(MissingRib, SameInputSameGcode) { EXPECT_EQ(emit(kSample).gcode, emit(kSample).gcode); }

TEST(MissingRib, SampleJobHasNoCrossingAndOneStrandPerLayer) {
  const auto job = nlohmann::json::parse(slicer::read_file(STRAND_SOURCE_DIR "/samples/missing-rib.json"));
  ASSERT_EQ(job.at("generator"), "missing-rib");
  ASSERT_EQ(job.at("machine"), "deltawasp-2040-clay");
  nlohmann::json given = job.at("params");
  const auto e = emit(given);
  expect_sound(e, "samples/missing-rib.json");
  // The only touch is where each closed strand ends on its own start: elsewhere, passes
  // through a node stay a nozzle apart.
  const auto touches = post::find_contacts(e.parsed.program, 0.01, 1e-3).touches;
  EXPECT_EQ(touches.size(), e.toolpath.layers.size());
  for (const auto& t : touches) {
    const slicer::Vec2 start = e.toolpath.layers[static_cast<std::size_t>(t.layer)].strokes[0].start_mm;
    EXPECT_LT((t.at_mm - start).norm(), 2e-3) << "touch in layer " << t.layer << " at " << t.at_mm.transpose();
  }
}

std::string error_of(const nlohmann::json& given) {
  return testing::input_error_of(missing_rib_table(), find_generator("missing-rib")->generate, given);
}

slicer::Toolpath wrap_missing_rib(const nlohmann::json& given, double period_mm) {
  return find_generator("missing-rib")
      ->generate_wrapped(slicer::resolve_params(missing_rib_table(), given), period_mm);
}

TEST(MissingRibWrap, SampleLatticeClosesRoundACylinder) {
  const double period = 2 * M_PI * 15;  // 94.25 mm: 10.03 pitches of 9.40 mm -> 10 of 9.42
  const auto t = wrap_missing_rib(kSample, period);
  testing::expect_sound_wrap(t, period);
  EXPECT_EQ(t.derived.at("cells_around").get<int>(), 10);
  EXPECT_EQ(t.derived.at("nodes").get<int>(), 5 * 10);
  const double c = std::cos(slicer::deg_to_rad(20.0));
  EXPECT_NEAR(t.derived.at("rib_mm").get<double>(), period / 10 / (2 * c), 1e-12)
      << "the rib adjusted at the same angle";
  EXPECT_NEAR(t.derived.at("footprint_mm")[0].get<double>(), period, 1e-12);
  EXPECT_GE(testing::wrapped_min_gap(t.layers[0], period), 0.6 - 2e-3)
      << "filaments that are not joined keep a nozzle apart, across the seam too";
  EXPECT_GT(testing::seam_pieces(t.layers[0].strokes[0], period).size(), 2u);
}

TEST(MissingRibWrap, ThirtyRandomSleevesAreSoundAndKeepANozzleApart) {
  std::mt19937 rng(1104);
  std::uniform_real_distribution<double> nozzle(0.4, 0.84), angle(1.0, 40.0), stretch(1.0, 1.8),
      around(4.0, 16.0);
  for (int i = 0; i < 30; ++i) {
    const double d = nozzle(rng), theta = angle(rng);
    MissingRibParams p;
    p.nozzle_mm = d;
    p.angle_deg = theta;
    p.node_gap_mm = d;
    const double rib = std::ceil(missing_rib_min_rib_mm(p) * stretch(rng) * 100) / 100;
    const nlohmann::json given = {{"nozzle", d}, {"rib", rib}, {"angle", theta},
                                  {"rows", 1 + static_cast<int>(rng() % 4)}, {"layers", 2}};
    const double period = around(rng) * 2 * rib * std::cos(slicer::deg_to_rad(theta));
    SCOPED_TRACE(given.dump() + " period " + std::to_string(period));
    const auto t = wrap_missing_rib(given, period);
    testing::expect_sound_wrap(t, period);
    EXPECT_EQ(t.derived.at("cells_around").get<int>() % 2, 0);
    EXPECT_GE(testing::wrapped_min_gap(t.layers[0], period), d - 2e-3);
  }
}

TEST(MissingRibWrap, TooSmallACircumferenceNamesWrapAndTheLimit) {
  MissingRibParams p;
  p.nozzle_mm = 0.6;
  p.angle_deg = 20;
  p.node_gap_mm = 0.6;
  const double min_pitch = 2 * missing_rib_min_rib_mm(p) * std::cos(slicer::deg_to_rad(20.0));
  EXPECT_NO_THROW(wrap_missing_rib(kSample, 4 * min_pitch + 1e-6)) << "the rib shrinks to fit";
  try {
    wrap_missing_rib(kSample, 4 * min_pitch - 0.01);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("missing-rib.wrap = full: "), std::string::npos) << m;
    EXPECT_NE(m.find("at least 4 cells around (an even number"), std::string::npos) << m;
  }
}

TEST(MissingRibParams, RibTooShortForTheNozzleNamesTheLimit) {
  auto bad = kSample;
  // At 20 deg and d 0.6 the corner-cut rule binds: 0.6 / cos 20 + 0.6 / sqrt 2 = 1.06276 >
  // 0.6 / (cos 20 - sin 20) = 1.00389.
  bad["rib"] = 0.8;
  const std::string msg = error_of(bad);
  EXPECT_NE(msg.find("missing-rib.rib = 0.8: must be >= 1.0628 at nozzle 0.6 and angle 20"), std::string::npos) << msg;
  auto ok = kSample;
  ok["rib"] = 1.0628;
  EXPECT_EQ(error_of(ok), "");
  // At 40 deg the bends bind: 0.6 / (cos 40 - sin 40) = 4.86788.
  bad["angle"] = 40;
  bad["rib"] = 4.8;
  EXPECT_NE(error_of(bad).find("must be >= 4.8679"), std::string::npos) << error_of(bad);
}

TEST(MissingRibParams, AngleOutsideOpenZeroToFortyFiveIsRejected) {
  for (double a : {0.0, 45.0, 60.0, -5.0}) {
    auto bad = kSample;
    bad["angle"] = a;
    const std::string msg = error_of(bad);
    EXPECT_NE(msg.find("missing-rib.angle"), std::string::npos) << a << ": " << msg;
    EXPECT_NE(msg.find("(0, 45)"), std::string::npos) << msg;
  }
}

TEST(MissingRib, NodeGapZeroPassesMeetOnTheNodesWithoutCrossing) {
  auto given = kSample;
  given["node-gap"] = 0;
  const auto e = emit(given);
  const auto c = post::find_contacts(e.parsed.program, 0.01, 1e-3);
  EXPECT_TRUE(c.crossings.empty()) << c.crossings.size() << " crossings";
  const double p = e.toolpath.derived.at("pitch_mm").get<double>();
  std::set<std::pair<long, long>> touched;  // nodes (i, j) where two passes meet
  for (const auto& t : c.touches) {
    if (t.layer != 0) continue;
    const double fi = t.at_mm.y() / p + 2.0, fj = t.at_mm.x() / p + 2.5;  // 4 x 5 cells, centred
    const long i = std::lround(fi), j = std::lround(fj);
    const bool on_node = std::abs(fi - i) * p < 2e-3 && std::abs(fj - j) * p < 2e-3;
    const bool at_start = (t.at_mm - e.toolpath.layers[0].strokes[0].start_mm).norm() < 2e-3;
    EXPECT_TRUE(on_node || at_start) << "touch away from the nodes at " << t.at_mm.transpose();
    if (on_node) touched.insert({i, j});
  }
  EXPECT_EQ(touched.size(), 5u * 6u) << "the two passes meet on every node";
  for (const auto& seg : e.toolpath.layers[0].strokes[0].segments) EXPECT_NE(seg.feature, slicer::Feature::Node);
}

TEST(MissingRibParams, NodeGapAboveTheNozzleIsRejected) {
  auto bad = kSample;
  bad["node-gap"] = 0.7;
  EXPECT_NE(error_of(bad).find("missing-rib.node-gap = 0.7: must be in [0, nozzle] = [0, 0.6]"), std::string::npos)
      << error_of(bad);
}

TEST(MissingRibParams, RowsAndColsAtLeastOne) {
  auto bad = kSample;
  bad["rows"] = 0;
  EXPECT_NE(error_of(bad).find("missing-rib.rows = 0"), std::string::npos);
  bad = kSample;
  bad["cols"] = -2;
  EXPECT_NE(error_of(bad).find("missing-rib.cols = -2"), std::string::npos);
}

TEST(MissingRibParams, TooLargeForTheDeltaNamesTheRadius) {
  auto big = kSample;
  big["rows"] = 30;
  big["cols"] = 30;
  EXPECT_NE(error_of(big).find("radius"), std::string::npos) << error_of(big);
}

TEST(MissingRibParams, HeightOrLayersExactlyOne) {
  auto both = kSample;
  both["height"] = 3;
  EXPECT_NE(error_of(both).find("not both"), std::string::npos);
  auto by_height = kSample;
  by_height.erase("layers");
  by_height["height"] = 2.4;  // 2.4 / (0.8 * 0.6) = 5 layers
  EXPECT_EQ(emit(by_height).parsed.program.layers.size(), 5u);
}

}  // namespace
}  // namespace strand::patterns
