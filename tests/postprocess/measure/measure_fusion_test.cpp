// Fused lengths and classes measured in synthetic photos of a generated fusion test: the
// meander drawn from the test's own path with ink spread to a known width, so pairs closer
// than that width are fused along their whole zone and wider ones are separate.
#include "postprocess/measure/measure_fusion.h"

#include <gtest/gtest.h>

#include "patterns/registry.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"
#include "tests/postprocess/measure/synthetic_photo.h"

namespace strand::testing {
namespace {

struct FusionPrint {
  nlohmann::json report;
  cv::Mat photo;
};

FusionPrint printed(const nlohmann::json& given, double width_mm, const PhotoSetup& s = {}) {
  const auto* g = patterns::find_generator("fusion-test");
  const auto t = slicer::collect(*g->layers(slicer::resolve_params(g->table(), given)));
  Canvas c = bed_canvas(t.derived, s);
  draw_toolpath(c, t, width_mm);
  return {{{"derived", t.derived}}, photograph(c, s)};
}

void expect_classes(const nlohmann::json& measured, double width_mm) {
  double closest = 1e300;
  for (const auto& s : measured["spacings"]) {
    const double spacing = s["spacing_mm"], zone = s["zone_length_mm"];
    const bool fused = spacing < width_mm;
    EXPECT_EQ(s["class"], fused ? "fused" : "separate") << s.dump();
    EXPECT_NEAR(s["fused_length_mm"].get<double>(), fused ? zone : 0.0, 0.05 * zone) << s.dump();
    if (!fused) closest = std::min(closest, spacing);
  }
  EXPECT_DOUBLE_EQ(measured["closest_separate_spacing_mm"].get<double>(), closest);
}

TEST(MeasureFusion, ClassesRightThroughTiltBlurNoiseAndUnevenLight) {
  // Spacings 2.4 to 0.6 by 0.3 and beads 1.0 mm wide: 0.6 and 0.9 overlap, 1.2 leaves 0.2 mm.
  const auto p = printed({{"nozzle", 0.6}}, 1.0);
  const auto m = post::measure::measure_fusion(p.photo, p.report, "photo");
  ASSERT_EQ(m.json["spacings"].size(), 7u);
  expect_classes(m.json, 1.0);
}

TEST(MeasureFusion, LightInkWiderBeadsTheOtherTilt) {
  PhotoSetup s;
  s.dark_ink = false;
  s.tilt_deg = -7.0;
  s.turn_deg = -4.0;
  s.scale = 0.8;
  const auto p = printed({{"nozzle", 0.5}, {"spacing-start", 2.5}, {"spacing-end", 0.5}, {"spacing-step", 0.4}}, 1.5, s);
  const auto m = post::measure::measure_fusion(p.photo, p.report, "photo");
  ASSERT_EQ(m.json["spacings"].size(), 6u);
  expect_classes(m.json, 1.5);
}

TEST(MeasureFusion, AReportOfAnotherTestIsRefused) {
  const auto p = printed({{"nozzle", 0.6}}, 1.0);
  try {
    post::measure::measure_fusion(p.photo, {{"derived", {{"test", "pore"}}}}, "photo");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not a fusion-test report"), std::string::npos) << e.what();
  }
}

// Remakes samples/ink/fusion-test-photo.jpg (the docs' walk-through measures it):
// strand_tests --gtest_also_run_disabled_tests --gtest_filter='*WriteFusionSamplePhoto'
TEST(MeasureFusion, DISABLED_WriteFusionSamplePhoto) {
  const auto p = printed({{"nozzle", 0.6}}, 1.0);
  slicer::write_file_atomic(std::string(STRAND_SOURCE_DIR) + "/samples/ink/fusion-test-photo.jpg", encode_jpeg(p.photo));
}

}  // namespace
}  // namespace strand::testing
