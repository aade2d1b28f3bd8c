// Fitting whole cells round a circumference, and the cylinder-topology checker the wrapped
// designs are tested with (it must see a crossing that exists only across the seam).
#include "patterns/wrap_fit.h"

#include <gtest/gtest.h>

#include <cmath>

#include "slicer/input_error.h"
#include "tests/support/wrap_checks.h"

namespace strand::patterns {
namespace {

std::string error_of(double period, double cell, const WrapRule& rule) {
  try {
    fit_around("demo", period, cell, rule);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(WrapFit, NearestMultipleOfTheStepAndTheCellThatCloses) {
  const WrapFit f = fit_around("demo", 100.0, 9.0, {3, 2, 500, 1.0, ""});
  EXPECT_EQ(f.cells, 12);  // 11.1 cells -> nearest even
  EXPECT_NEAR(f.cell_mm * f.cells, 100.0, 1e-12);
  EXPECT_EQ(fit_around("demo", 100.0, 9.0, {3, 1, 500, 1.0, ""}).cells, 11);
}

TEST(WrapFit, RoundsDownWhenTheNearestCountMakesTooSmallACell) {
  // 100 / 9.4 = 10.6 -> 11 cells of 9.09 mm, below the 9.2 mm minimum: 10 of 10 mm instead
  const WrapFit f = fit_around("demo", 100.0, 9.4, {3, 1, 500, 9.2, ""});
  EXPECT_EQ(f.cells, 10);
  EXPECT_NEAR(f.cell_mm, 10.0, 1e-12);
  EXPECT_NEAR(f.requested_cell_mm, 9.4, 1e-12);
}

TEST(WrapFit, RoundsUpWhenTheNearestCountMakesTooLargeACell) {
  // 100 / 9.6 = 10.4 -> 10 cells of 10 mm, above a 9.9 mm maximum: 11 of 9.09 mm instead
  WrapRule rule{3, 1, 500, 1.0, ""};
  rule.max_cell_mm = 9.9;
  EXPECT_EQ(fit_around("demo", 100.0, 9.6, rule).cells, 11);
  rule.min_cell_mm = 9.5;  // nothing between 9.5 and 9.9 divides 100 mm
  try {
    fit_around("demo", 100.0, 9.6, rule);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "demo.wrap = full: a 100 mm circumference holds no whole number of cells between "
              "9.5 mm and 9.9 mm; change the circumference or the cell");
  }
}

TEST(WrapFit, ImpossibleCircumferencesNameWrapAndTheLimit) {
  const WrapRule rule{4, 2, 500, 6.0, "an even number"};
  EXPECT_EQ(error_of(23.0, 6.0, rule),
            "demo.wrap = full: a 23 mm circumference is too small: at least 4 cells around (an "
            "even number) of at least 6 mm need 24 mm");
  EXPECT_EQ(error_of(24.0, 6.0, rule), "");
  EXPECT_NE(error_of(-1.0, 6.0, rule).find("must be > 0 mm"), std::string::npos);
  EXPECT_NE(error_of(5000.0, 6.0, rule).find("at most 500"), std::string::npos);
  EXPECT_NE(error_of(1e12, 1e-6, rule).find("more than 500"), std::string::npos);
}

TEST(WrapFit, ReportKeysSayTheAdjustedCell) {
  nlohmann::json d;
  add_wrap_report(d, fit_around("demo", 100.0, 9.0, {3, 2, 500, 1.0, ""}), "node spacing");
  EXPECT_EQ(d.at("cells_around"), 12);
  EXPECT_NEAR(d.at("cell_around_mm").get<double>(), 100.0 / 12, 1e-12);
  EXPECT_EQ(d.at("wrap_fit"),
            "node spacing adjusted from 9 to 8.3333 mm so 12 cells close round the circumference");
}

slicer::Layer layer_of(const std::vector<slicer::Vec2>& pts) {
  slicer::Stroke s;
  s.start_mm = pts.front();
  for (std::size_t i = 1; i < pts.size(); ++i)
    s.segments.push_back(slicer::line_to(pts[i], slicer::Feature::Ligament));
  return {0.4, 0.4, {s}};
}

TEST(WrapChecks, SeesACrossingThatExistsOnlyAcrossTheSeam) {
  // period 10: a segment from x = 4 to 6 (past the seam at 5) and, drawn near x = -5, one
  // crossing its copy: flat they are 10 mm apart, on the cylinder they cross at x = +-5.
  const auto layer = layer_of({{4, 0}, {6, 0}, {6, 3}, {-5, 3}, {-5, -1}});
  const auto crossings = testing::wrapped_crossings(layer, 10.0);
  ASSERT_EQ(crossings.size(), 1u);
  EXPECT_NEAR(std::abs(crossings[0].x()), 5.0, 1e-12);
  EXPECT_NEAR(crossings[0].y(), 0.0, 1e-12);
  EXPECT_TRUE(
      testing::wrapped_crossings(layer_of({{4, 0}, {6, 0}, {6, 3}, {-3, 3}, {-3, -1}}), 10.0)
          .empty());
}

TEST(WrapChecks, SeamPiecesStayInOnePeriodAndMeetAcrossTheSeam) {
  const auto layer = layer_of({{0, 0}, {12, 1}, {-7, 2}});
  const auto pieces = testing::seam_pieces(layer.strokes[0], 10.0);
  EXPECT_EQ(pieces.size(), 4u);  // crosses x = 5, then on the way back x = 5 and x = -5
  for (const auto& p : pieces) {
    for (const auto& q : p) EXPECT_LE(std::abs(q.x()), 5.0 + 1e-12);
  }
  EXPECT_LT(testing::largest_seam_gap(pieces, 10.0), 1e-12);
}

}  // namespace
}  // namespace strand::patterns
