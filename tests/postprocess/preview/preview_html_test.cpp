// HTML preview in a real browser: headless Chromium draws the toolpath (screenshot pixels)
// and the page's own status line reports success, with no console errors. Skips only
// when Chromium is not installed.
#include "postprocess/preview/preview_html.h"

#include <gtest/gtest.h>

#include <fstream>

#include "postprocess/inspect/gcode_parser.h"
#include "tests/support/chromium.h"
#include "tests/support/cli_runner.h"
#include "tests/support/png_pixels.h"

namespace strand::post {
namespace {

using strand::testing::slurp;

std::string sample_page(const std::string& dir) {
  std::string gcode = ";LAYER:0\nG0 X0 Y0 Z0.5\n;WIDTH:0.8\n";
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

}  // namespace
}  // namespace strand::post
