// HTML preview in a real browser: headless Chromium draws the toolpath (screenshot pixels)
// and the page's own status line reports success, with no console errors. Skips only
// when Chromium is not installed.
#include "postprocess/preview/preview_html.h"

#include <gtest/gtest.h>

#include <fstream>

#include "patterns/registry.h"
#include "postprocess/inspect/gcode_parser.h"
#include "slicer/params.h"
#include "tests/support/cylinder_scene.h"
#include "tests/support/chromium.h"
#include "tests/support/cli_runner.h"
#include "tests/support/png_pixels.h"

namespace strand::post {
namespace {

using strand::testing::slurp;

// A 20 x 20 mm filled square; `purge` adds an intro line far away before the first layer.
std::string sample_page(const std::string& dir, bool purge = false) {
  std::string gcode = purge ? "G1 X-300 Y-300 Z0.3 F1000\nG1 X-200 Y-300 E5\n" : "";
  gcode += ";LAYER:0\nG0 X0 Y0 Z0.5\n;WIDTH:0.8\n";
  for (int i = 0; i <= 20; ++i) {  // a serpentine filling 20 x 20 mm
    gcode += "G1 X" + std::to_string(i % 2 ? 0 : 20) + " Y" + std::to_string(i) + " E" + std::to_string(2 * i + 1) + "\n";
    gcode += "G1 Y" + std::to_string(i + 1) + " E" + std::to_string(2 * i + 2) + "\n";
  }
  const std::string path = dir + "/preview.html";
  std::ofstream(path) << render_html(preview_scene(parse_gcode(gcode).program, 0.01), "serpentine.gcode");
  return path;
}

TEST(PreviewHtml, IsSelfContained) {
  const std::string page = slurp(sample_page(strand::testing::fresh_dir("html-self")));
  EXPECT_EQ(page.find("http://"), std::string::npos);
  EXPECT_EQ(page.find("https://"), std::string::npos);
  EXPECT_EQ(page.find("src="), std::string::npos);
  for (const char* control : {"id=\"layer\"", "id=\"travel\"", "wheel", "mousedown"}) {
    EXPECT_NE(page.find(control), std::string::npos) << control;
  }
}

TEST(PreviewHtml, ChromiumDrawsTheToolpathWithoutConsoleErrors) {
  if (strand::testing::chromium_path().empty()) GTEST_SKIP() << "chromium is not installed (apt-get install chromium)";
  const auto dir = strand::testing::fresh_dir("html-chromium");
  const std::string page = sample_page(dir);
  const auto dom = strand::testing::run_chromium(dir, "--dump-dom", page);
  EXPECT_EQ(dom.exit_code, 0);
  EXPECT_NE(dom.out.find("drawn: 1 paths, layers 0-0"), std::string::npos) << dom.out.substr(0, 400);
  EXPECT_FALSE(strand::testing::has_console_output(dom.log)) << dom.log;
  const auto shot = strand::testing::run_chromium(dir, "--screenshot='" + dir + "/shot.png'", page);
  EXPECT_FALSE(strand::testing::has_console_output(shot.log)) << shot.log;
  const auto st = strand::testing::png_stats(slurp(dir + "/shot.png"));
  ASSERT_GT(st.width, 0) << "no screenshot";
  // The filled 20 x 20 mm square takes a good part of the 900 x 700 window.
  EXPECT_GT(st.drawn_fraction, 0.2);
}

// Screenshot stats of `page` (with an optional "#..." view in the URL), after checking that
// the page logged nothing.
strand::testing::PngStats shot_of(const std::string& dir, const std::string& page,
                                  std::string* png = nullptr) {
  static int n = 0;
  const std::string file = dir + "/shot" + std::to_string(n++) + ".png";
  const auto run = strand::testing::run_chromium(dir, "--screenshot='" + file + "'", page);
  EXPECT_FALSE(strand::testing::has_console_output(run.log)) << run.log;
  if (png) *png = slurp(file);
  return strand::testing::png_stats(slurp(file));
}

TEST(PreviewHtml, FitsThePartNotAPurgeLine) {
  if (strand::testing::chromium_path().empty()) GTEST_SKIP() << "chromium is not installed";
  const auto dir = strand::testing::fresh_dir("html-purge");
  EXPECT_GT(shot_of(dir, sample_page(dir, true)).drawn_fraction, 0.2)
      << "the square fills the window as without the intro line 300 mm away";
}

TEST(PreviewHtml, ThisLayerOnlyRefitsAndZLabelsAreRounded) {
  if (strand::testing::chromium_path().empty()) GTEST_SKIP() << "chromium is not installed";
  const auto dir = strand::testing::fresh_dir("html-only");
  // layer 0: a 100 mm outline; layer 1 at z 0.30000000000000004: a filled 10 mm square
  std::string gcode = ";LAYER:0\n;Z:0.2\n;WIDTH:0.8\nG0 X0 Y0 Z0.2\nG1 X100 E1\nG1 Y100 E2\nG1 X0 E3\nG1 Y0 E4\n"
                      ";LAYER:1\n;Z:0.30000000000000004\nG0 X0 Y0 Z0.3\n";
  for (int i = 0; i <= 12; ++i) {
    gcode += "G1 X" + std::to_string(i % 2 ? 0 : 10) + " Y" + std::to_string(i * 0.8) + " E" + std::to_string(5 + i) + "\n";
  }
  const std::string page = dir + "/only.html";
  std::ofstream(page) << render_html(preview_scene(parse_gcode(gcode).program, 0.01), "only.gcode");
  const auto dom = strand::testing::run_chromium(dir, "--dump-dom", page + "#layer=1&only=1");
  EXPECT_NE(dom.out.find("1 (z 0.3 mm)"), std::string::npos) << dom.out.substr(0, 600);
  EXPECT_NE(dom.out.find("drawn: 1 paths, layers 1-1"), std::string::npos);
  const double all = shot_of(dir, page + "#layer=1").drawn_fraction;
  const double only = shot_of(dir, page + "#layer=1&only=1").drawn_fraction;
  EXPECT_GT(only, 0.2) << "the 10 mm square alone fills the window";
  EXPECT_GT(only, 3 * all);
}

// A tetrachiral sleeve on a test cylinder (the mapping of tests/support/cylinder_scene.h).
std::string sleeve_page(const std::string& dir) {
  const auto* g = patterns::find_generator("tetrachiral");
  const auto t = g->generate_wrapped(
      slicer::resolve_params(g->table(), {{"nozzle", 0.5}, {"cell", 10}, {"rows", 3}, {"layers", 2}, {"grip", 4}}),
      2 * M_PI * 12);
  const std::string page = dir + "/sleeve.html";
  std::ofstream(page) << render_html(strand::testing::cylinder_scene(t, 12.0, 60.0), "sleeve");
  return page;
}

TEST(PreviewHtml, SleeveOnACylinderGetsAnOrbitViewOverATranslucentSubstrate) {
  const auto dir = strand::testing::fresh_dir("html-orbit");
  const std::string page = sleeve_page(dir);
  const std::string html = slurp(page);
  EXPECT_NE(html.find("\"dim\":3"), std::string::npos);
  EXPECT_NE(html.find("\"substrate\":{\"v\":["), std::string::npos);
  EXPECT_EQ(html.find("http"), std::string::npos) << "self-contained";
  if (strand::testing::chromium_path().empty()) GTEST_SKIP() << "chromium is not installed";
  const auto dom = strand::testing::run_chromium(dir, "--dump-dom", page);
  EXPECT_NE(dom.out.find("layers 0-1 (3D orbit view)"), std::string::npos) << dom.out.substr(0, 600);
  EXPECT_NE(dom.out.find("1 (offset 0.8 mm)"), std::string::npos);
  EXPECT_FALSE(strand::testing::has_console_output(dom.log)) << dom.log;
  std::string front, side;
  shot_of(dir, page, &front);
  shot_of(dir, page + "#yaw=90&pitch=0", &side);
  const Rgb lig = feature_colour(slicer::Feature::Ligament);
  auto ligament = [&](const std::string& png) {
    return strand::testing::colour_spot(png, static_cast<int>(lig.r * 255), static_cast<int>(lig.g * 255),
                                        static_cast<int>(lig.b * 255), 40);
  };
  EXPECT_GT(ligament(front).count, 2000);
  // the substrate: translucent grey over white where no path is, both near and far walls
  EXPECT_GT(strand::testing::colour_spot(front, 210, 213, 219, 30).count, 5000);
  // orbiting to look along the axis shows the sleeve end-on: a ring, not a long tube
  const auto end_on = strand::testing::png_stats(side), long_side = strand::testing::png_stats(front);
  EXPECT_NE(front, side);
  EXPECT_GT(ligament(side).count, 500);
  EXPECT_LT(end_on.drawn_fraction, long_side.drawn_fraction);
}

}  // namespace
}  // namespace strand::post
