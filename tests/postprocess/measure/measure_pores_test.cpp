// Pr of every pore measured in synthetic photos of a generated pore test: the log-pile drawn
// from the test's own path with ink spread wider than the nozzle and pore corners filled to
// known radii (square to round), then tilted, blurred, noisy, unevenly lit.
#include "postprocess/measure/measure_pores.h"

#include <gtest/gtest.h>

#include "patterns/registry.h"
#include "postprocess/measure/measure_job.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"
#include "tests/postprocess/measure/synthetic_photo.h"

namespace strand::testing {
namespace {

struct PoreTruth {
  double side_mm = 0.0, radius_mm = 0.0;
  double pr() const {
    const double k = 4 - CV_PI;
    const double l = 4 * side_mm - 2 * k * radius_mm, a = side_mm * side_mm - k * radius_mm * radius_mm;
    return l * l / (16 * a);
  }
};

struct PorePrint {
  nlohmann::json report;
  std::vector<PoreTruth> truth;
  cv::Mat photo;
};

// Signed distance from p to a rounded square (centre c, half side h, corner radius r); < 0 inside.
double rounded_square_distance(const cv::Point2d& p, const cv::Point2d& c, double h, double r) {
  const double dx = std::abs(p.x - c.x) - (h - r), dy = std::abs(p.y - c.y) - (h - r);
  return std::hypot(std::max(dx, 0.0), std::max(dy, 0.0)) + std::min(std::max(dx, dy), 0.0) - r;
}

// Beads `spread` x the nozzle wide; pore k's corners filled to radius (k % 5) / 8 x its side
// (the fifth a circle), and pore `filled` (if any) all ink.
PorePrint printed(const nlohmann::json& given, double spread, const PhotoSetup& s, int filled = -1) {
  const auto* g = patterns::find_generator("pore-test");
  const auto t = slicer::collect(*g->layers(slicer::resolve_params(g->table(), given)));
  PorePrint out;
  out.report = {{"derived", t.derived}};
  const double nozzle = t.derived["nozzle_mm"], w = spread * nozzle, pitch = t.derived["pitch_mm"];
  Canvas c = bed_canvas(t.derived, s);
  draw_toolpath(c, t, w);
  const double side = pitch - w;
  for (const auto& p : t.derived["pores"]) {
    const int k = p["index"];
    const double r = (k % 5) * side / 8;
    const cv::Point2d centre(p["centre_mm"][0], p["centre_mm"][1]);
    const cv::Point2d half(side / 2 + 0.1, side / 2 + 0.1);
    if (k == filled) {
      c.paint(centre - half, centre + half, [](const cv::Point2d&) { return 1.0; });
    } else {
      c.paint(centre - half, centre + half,
              [&](const cv::Point2d& q) { return 0.5 + rounded_square_distance(q, centre, side / 2, r) * c.ppm; });
    }
    out.truth.push_back({side, r});
  }
  out.photo = photograph(c, s);
  return out;
}

// A photo as a phone takes a 25 mm print: about 30 pixels per millimetre.
PhotoSetup pore_camera() {
  PhotoSetup s;
  s.render_px_per_mm = 40.0;
  s.scale = 0.75;
  return s;
}

void expect_pr_within(const post::measure::Measured& m, const std::vector<PoreTruth>& truth, double tolerance) {
  const auto& pores = m.json["pores"];
  ASSERT_EQ(pores.size(), truth.size());
  double mean = 0.0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    ASSERT_EQ(pores[i]["status"], "measured") << i;
    EXPECT_NEAR(pores[i]["pr"].get<double>(), truth[i].pr(), tolerance * truth[i].pr()) << "pore " << i << " " << pores[i].dump();
    mean += truth[i].pr() / static_cast<double>(truth.size());
  }
  EXPECT_NEAR(m.json["mean_pr"].get<double>(), mean, tolerance * mean);
}

TEST(MeasurePores, PrWithinThreePercentFromSquareToRoundThroughTiltBlurNoiseAndLight) {
  const auto p = printed({{"nozzle", 0.6}}, 1.15, pore_camera());
  const auto m = post::measure::measure_pores(p.photo, p.report, "photo");
  expect_pr_within(m, p.truth, 0.03);
  EXPECT_EQ(m.json["pores_measured"], 16);
}

TEST(MeasurePores, LightInkOnADarkBedTheOtherTiltThreeLayers) {
  PhotoSetup s = pore_camera();
  s.dark_ink = false;
  s.tilt_deg = -6.0;
  s.turn_deg = -5.0;
  s.scale = 0.9;
  const auto p = printed({{"nozzle", 0.4}, {"pores", 3}, {"pore-size", 2}, {"layers", 3}}, 1.3, s);
  expect_pr_within(post::measure::measure_pores(p.photo, p.report, "photo"), p.truth, 0.03);
}

TEST(MeasurePores, AFilledPoreIsReportedNotMeasured) {
  const auto p = printed({{"nozzle", 0.6}, {"pores", 2}}, 1.15, pore_camera(), 1);
  const auto m = post::measure::measure_pores(p.photo, p.report, "photo");
  EXPECT_EQ(m.json["pores"][1]["status"], "filled");
  EXPECT_TRUE(m.json["pores"][1]["pr"].is_null());
  EXPECT_EQ(m.json["pores_measured"], 3);
}

TEST(MeasurePores, AnotherTestsReportOrNoMarksIsOneClearError) {
  PhotoSetup s = pore_camera();
  const auto p = printed({{"nozzle", 0.6}, {"pores", 2}}, 1.15, s);
  nlohmann::json lines = {{"derived", {{"test", "lines"}}}};
  try {
    post::measure::measure_test(p.photo, "pore", lines, "photo");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("measure.test = pore: the job report is of the lines test"), std::string::npos) << e.what();
  }
  s.draw_marks = false;
  const auto bare = printed({{"nozzle", 0.6}, {"pores", 2}}, 1.15, s);
  try {
    post::measure::measure_test(bare.photo, "pore", bare.report, "photo");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("found 0 of the 4 fiducial marks"), std::string::npos) << e.what();
  }
  EXPECT_THROW(post::measure::measure_test(p.photo, "collapse", p.report, "photo"), InputError);
}

// Remakes samples/ink/pore-test-photo.jpg (the docs' walk-through measures it):
// strand_tests --gtest_also_run_disabled_tests --gtest_filter='*WritePoreSamplePhoto'
TEST(MeasurePores, DISABLED_WritePoreSamplePhoto) {
  const auto p = printed({{"nozzle", 0.6}}, 1.15, pore_camera());
  slicer::write_file_atomic(std::string(STRAND_SOURCE_DIR) + "/samples/ink/pore-test-photo.jpg", encode_jpeg(p.photo));
}

}  // namespace
}  // namespace strand::testing
