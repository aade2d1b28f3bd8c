// The pore, fusion and collapse tests of issue 32: what each lays down matches what its
// report says a photo will be measured against, and bad input is refused in one line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "patterns/collapse_test.h"
#include "patterns/fusion_test.h"
#include "patterns/pore_test.h"
#include "patterns/registry.h"
#include "slicer/input_error.h"

namespace strand::patterns {
namespace {

slicer::Toolpath make(const std::string& name, const nlohmann::json& given) {
  const auto* g = find_generator(name);
  return g->generate(slicer::resolve_params(g->table(), given));
}

std::string error_of(const std::string& name, const nlohmann::json& given) {
  try {
    make(name, given);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

slicer::Vec2 vec(const nlohmann::json& xy) { return {xy[0].get<double>(), xy[1].get<double>()}; }

double distance_to_segment(const slicer::Vec2& p, const slicer::Vec2& a, const slicer::Vec2& b) {
  const slicer::Vec2 d = b - a;
  const double t = std::clamp((p - a).dot(d) / d.dot(d), 0.0, 1.0);
  return (a + t * d - p).norm();
}

// Distance from `p` to the nearest bead centre line of the layers' strokes, marks left out.
double nearest_bead(const slicer::Toolpath& t, const slicer::Vec2& p) {
  double best = 1e300;
  for (const auto& l : t.layers) {
    for (const auto& s : l.strokes) {
      slicer::Vec2 a = s.start_mm;
      for (const auto& seg : s.segments) {
        if (seg.feature != slicer::Feature::Frame) best = std::min(best, distance_to_segment(p, a, seg.end_mm));
        a = seg.end_mm;
      }
    }
  }
  return best;
}

std::size_t strokes_without_marks(const slicer::Layer& l) {
  return std::count_if(l.strokes.begin(), l.strokes.end(),
                       [](const auto& s) { return s.segments.front().feature != slicer::Feature::Frame; });
}

TEST(PoreTest, EveryPoreIsAnOpenSquareOfItsSideBetweenNozzleWideFilaments) {
  const auto t = make("pore-test", {{"nozzle", 0.6}, {"pores", 3}, {"pore-size", 2.0}, {"layers", 3}});
  ASSERT_EQ(t.layers.size(), 3u);
  for (const auto& l : t.layers) EXPECT_EQ(strokes_without_marks(l), 1u) << "one serpentine per layer";
  EXPECT_EQ(t.layers[0].strokes.size(), 5u) << "the marks in the first layer";
  EXPECT_EQ(t.derived["fiducials"].size(), 4u);
  const auto& pores = t.derived["pores"];
  ASSERT_EQ(pores.size(), 9u);
  for (const auto& p : pores) {
    const slicer::Vec2 c = vec(p["centre_mm"]);
    const double half = p["side_mm"].get<double>() / 2;
    EXPECT_DOUBLE_EQ(half, 1.0);
    // The bead edges (half a nozzle off the centre lines) meet the pore's sides exactly.
    EXPECT_NEAR(nearest_bead(t, c), half + 0.3, 1e-9) << p.dump();
    for (const slicer::Vec2& corner : {slicer::Vec2(half, half), slicer::Vec2(-half, half), slicer::Vec2(half, -half),
                                      slicer::Vec2(-half, -half)}) {
      EXPECT_NEAR(nearest_bead(t, c + corner), 0.3, 1e-9) << p.dump();
    }
  }
  // The layers alternate: the first along x, the second along y.
  const auto& s0 = t.layers[0].strokes[0];
  const auto& s1 = t.layers[1].strokes[0];
  EXPECT_DOUBLE_EQ(s0.segments[0].end_mm.y(), s0.start_mm.y());
  EXPECT_DOUBLE_EQ(s1.segments[0].end_mm.x(), s1.start_mm.x());
}

TEST(PoreTest, DefaultsAndRefusals) {
  const auto t = make("pore-test", {{"nozzle", 0.6}});
  EXPECT_EQ(t.derived["pores"].size(), 16u);
  EXPECT_EQ(t.layers.size(), 2u);
  EXPECT_DOUBLE_EQ(t.derived["pores"][0]["side_mm"].get<double>(), 1.8);
  EXPECT_NE(error_of("pore-test", {{"nozzle", 0.6}, {"layers", 1}}).find("pore-test.layers = 1"), std::string::npos);
  EXPECT_NE(error_of("pore-test", {{"nozzle", 0.6}, {"pore-size", 0.4}}).find("pore-test.pore-size = 0.4: must be >= nozzle = 0.6"),
            std::string::npos);
  EXPECT_NE(error_of("pore-test", {{"nozzle", 0.6}, {"fiducial-size", 1}}).find("pore-test.fiducial-size = 1: must be >= 4 x nozzle = 2.4"),
            std::string::npos);
  EXPECT_NE(error_of("pore-test", nlohmann::json::object()).find("pore-test.nozzle: missing"), std::string::npos);
}

TEST(FusionTest, OneMeanderWhoseSpacingShrinksByTheStep) {
  const auto t = make("fusion-test", {{"nozzle", 0.5}, {"spacing-start", 2}, {"spacing-end", 0.5}, {"spacing-step", 0.25}});
  ASSERT_EQ(t.layers.size(), 1u);
  EXPECT_EQ(strokes_without_marks(t.layers[0]), 1u) << "one strand";
  const auto& spacings = t.derived["spacings"];
  ASSERT_EQ(spacings.size(), 7u);
  const auto& meander = t.layers[0].strokes[0];
  // Filaments along y are every other segment; their x steps are the spacings in order.
  std::vector<double> xs = {meander.start_mm.x()};
  for (std::size_t k = 1; k < meander.segments.size(); k += 2) xs.push_back(meander.segments[k].end_mm.x());
  ASSERT_EQ(xs.size(), spacings.size() + 1);
  for (std::size_t k = 0; k < spacings.size(); ++k) {
    const double s = spacings[k]["spacing_mm"];
    EXPECT_NEAR(s, 2.0 - 0.25 * k, 1e-9);
    EXPECT_NEAR(xs[k + 1] - xs[k], s, 1e-9);
    // The measured zone runs along the mid-line, clear of both U-turns.
    const slicer::Vec2 a = vec(spacings[k]["start_mm"]), b = vec(spacings[k]["end_mm"]);
    EXPECT_NEAR(a.x(), (xs[k] + xs[k + 1]) / 2, 1e-9);
    EXPECT_NEAR(nearest_bead(t, a), s / 2, 1e-9);
    EXPECT_NEAR(nearest_bead(t, b), s / 2, 1e-9);
    EXPECT_GT(b.y() - a.y(), 5.0);
    EXPECT_GE(10.0 - b.y(), 2 * 2.0 - 1e-9);
  }
}

TEST(FusionTest, DefaultsAndRefusals) {
  const auto t = make("fusion-test", {{"nozzle", 0.6}});
  EXPECT_EQ(t.derived["spacings"].size(), 7u) << "2.4 to 0.6 by 0.3";
  EXPECT_NE(error_of("fusion-test", {{"nozzle", 0.6}, {"spacing-end", 0.3}}).find("fusion-test.spacing-end = 0.3: must be >= nozzle"),
            std::string::npos);
  EXPECT_NE(error_of("fusion-test", {{"nozzle", 0.6}, {"spacing-start", 0.5}, {"spacing-end", 1}}).find("fusion-test.spacing-start = 0.5"),
            std::string::npos);
  EXPECT_NE(error_of("fusion-test", {{"nozzle", 0.6}, {"spacing-step", 0.01}}).find("fusion-test.spacing-step = 0.01: gives more than 40"),
            std::string::npos);
  EXPECT_NE(error_of("fusion-test", {{"nozzle", 0.6}, {"length", 5}}).find("fusion-test.length = 5: must be >= 4 x spacing-start"),
            std::string::npos);
}

TEST(CollapseTest, PillarsWithTheGapsAndOneFilamentAcrossTheirTops) {
  const auto t = make("collapse-test", {{"nozzle", 0.6}, {"gaps", "1,3,6"}, {"layers", 4}, {"pillar-size", 3}});
  ASSERT_EQ(t.layers.size(), 4u);
  for (std::size_t k = 0; k + 1 < t.layers.size(); ++k) EXPECT_EQ(strokes_without_marks(t.layers[k]), 4u) << k;
  const auto& top = t.layers.back();
  ASSERT_EQ(top.strokes.size(), 1u);
  EXPECT_DOUBLE_EQ(top.z_mm, t.derived["filament_z_mm"].get<double>());
  const auto& gaps = t.derived["gaps"];
  ASSERT_EQ(gaps.size(), 3u);
  const double filament_x0 = top.strokes[0].start_mm.x(), filament_x1 = top.strokes[0].end_mm().x();
  for (std::size_t k = 0; k < gaps.size(); ++k) {
    const slicer::Vec2 a = vec(gaps[k]["start_mm"]), b = vec(gaps[k]["end_mm"]);
    EXPECT_NEAR(b.x() - a.x(), gaps[k]["gap_mm"].get<double>(), 1e-9);
    EXPECT_GT(a.x(), filament_x0);
    EXPECT_LT(b.x(), filament_x1);
    // Nothing under the span: every pillar bead's edge ends at a face of the gap.
    for (std::size_t l = 0; l + 1 < t.layers.size(); ++l) {
      for (const auto& s : t.layers[l].strokes) {
        slicer::Vec2 p = s.start_mm;
        for (const auto& seg : s.segments) {
          if (seg.feature == slicer::Feature::Frame) break;
          for (const slicer::Vec2& q : {p, seg.end_mm}) {
            EXPECT_FALSE(q.x() > a.x() - 0.3 + 1e-9 && q.x() < b.x() + 0.3 - 1e-9) << "gap " << k << " layer " << l;
          }
          p = seg.end_mm;
        }
      }
    }
  }
  EXPECT_NE(error_of("collapse-test", {{"nozzle", 0.6}, {"pillar-size", 1}}).find("collapse-test.pillar-size = 1: must be >= 3 x nozzle = 1.8"),
            std::string::npos);
  EXPECT_NE(error_of("collapse-test", {{"nozzle", 0.6}, {"layers", 1}}).find("collapse-test.layers = 1"), std::string::npos);
  EXPECT_NE(error_of("collapse-test", {{"nozzle", 0.6}, {"gaps", "0,2"}}).find("collapse-test.gaps"), std::string::npos);
  EXPECT_EQ(make("collapse-test", {{"nozzle", 0.6}}).derived["gaps"].size(), 5u);
}

}  // namespace
}  // namespace strand::patterns
