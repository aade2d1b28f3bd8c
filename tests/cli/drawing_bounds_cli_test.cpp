// Issue 24's drawing-side reproducers (images, tracing, `strand text` sizes) and issue 19's
// preview per pen: bounds end with exit code 2, one line naming the parameter or bound and no
// output file; pens keep their drawing's colours in previews.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "slicer/file_io.h"
#include "tests/support/cli_runner.h"
#include "tests/support/png_pixels.h"

namespace strand::testing {
namespace {

// A PNG signature and IHDR of a 20000 x 20000 1-bit grey image, the pixels not even given:
// the size alone must refuse it.
std::string huge_png_header() {
  const unsigned char bytes[] = {0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00,
                                 0x0d, 0x49, 0x48, 0x44, 0x52, 0x00, 0x00, 0x4e, 0x20, 0x00, 0x00,
                                 0x4e, 0x20, 0x01, 0x00, 0x00, 0x00, 0x00, 0xcb, 0x0b, 0x7b, 0x94};
  return std::string(reinterpret_cast<const char*>(bytes), sizeof bytes);
}

// A binary PGM checkerboard of single pixels: the worst case for potrace.
std::string checkerboard_pgm(int n) {
  std::string s = "P5\n" + std::to_string(n) + " " + std::to_string(n) + "\n255\n";
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) s += static_cast<char>((x + y) % 2 ? 255 : 0);
  }
  return s;
}

TEST(DrawingBounds, HugeImageIsRefusedBeforeDecoding) {
  const auto dir = fresh_dir("bounds-image");
  slicer::write_file_atomic(dir + "/big.png", huge_png_header());
  expect_input_error(run_strand("trace big.png -o out.svg", dir),
                     "image 20000 x 20000 px: must have at most 16777216 pixels");
  EXPECT_FALSE(exists(dir + "/out.svg"));
}

TEST(DrawingBounds, CheckerboardTraceIsRefusedBeforeTracing) {
  const auto dir = fresh_dir("bounds-trace");
  slicer::write_file_atomic(dir + "/checker.pgm", checkerboard_pgm(2000));
  expect_input_error(run_strand("trace checker.pgm --turdsize 0 -o out.svg", dir),
                     "8000000 pixel edges between ink and paper (at most 3000000)");
  EXPECT_FALSE(exists(dir + "/out.svg"));
  // a small one traces (each level's edges are counted, the bound is on their sum)
  slicer::write_file_atomic(dir + "/small.pgm", checkerboard_pgm(40));
  const auto ok = run_strand("trace small.pgm --turdsize 0 -o small.svg", dir);
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
}

TEST(DrawingBounds, PixelSizeBelowTheOutputResolutionIsRefused) {
  const auto dir = fresh_dir("bounds-pixel");
  slicer::write_file_atomic(dir + "/small.pgm", checkerboard_pgm(8));
  expect_input_error(run_strand("trace small.pgm --pixel-size 1e-9 -o out.svg", dir),
                     "trace.pixel-size = 1e-09: must be in [0.01, 100] (mm)");
  EXPECT_FALSE(exists(dir + "/out.svg"));
  EXPECT_EQ(run_strand("trace small.pgm --pixel-size 0.01 -o ok.svg", dir).exit_code, 0);
}

TEST(DrawingBounds, TextSizeAndLengthAreBounded) {
  const auto dir = fresh_dir("bounds-text");
  expect_input_error(run_strand("text hello --size 1e-9 -o out.svg", dir),
                     "text.size = 1e-09: must be in [0.1, 1000] (mm)");
  expect_input_error(run_strand("text hello --size 0.001 -o out.gcode", dir),
                     "text.size = 0.001: must be in [0.1, 1000] (mm)");
  std::string args = "text ";
  args.append(100000, 'x');
  args += " -o out.svg";
  expect_input_error(run_strand(args, dir),
                     "text: the string has 100000 characters (at most 20000)");
  EXPECT_FALSE(exists(dir + "/out.svg"));
  EXPECT_FALSE(exists(dir + "/out.gcode"));
  // the smallest size with 5,000 characters plots (it took 246 s at 0.001 mm)
  std::string words;
  for (int i = 0; i < 1000; ++i) words += "abcd ";
  const auto ok = run_strand("text \"" + words + "\" --size 0.1 -o ok.gcode", dir);
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
}

// Two pens with their own stroke colours: the plot's G-code names them, the preview draws
// each pen's strokes in its colour and lists both in the legend.
TEST(PreviewPerPen, EachPenDrawsInItsStrokeColour) {
  const auto dir = fresh_dir("preview-pens");
  std::ofstream(dir + "/two.svg")
      << "<svg xmlns='http://www.w3.org/2000/svg' width='100mm' height='100mm' "
         "viewBox='0 0 100 100'><g id='m1'><path d='M10 20 H90' stroke='#d40000' "
         "stroke-width='2'/></g><g id='m2'><path d='M10 80 H90' stroke='rgb(0,80,255)'/></g>"
         "</svg>";
  const auto plot = run_strand("plot two.svg --machine xy-plotter-servo -o two.gcode", dir);
  ASSERT_EQ(plot.exit_code, 0) << plot.err;
  const std::string gcode = slurp(dir + "/two.gcode");
  EXPECT_NE(gcode.find("; pen 1 colour: #d40000"), std::string::npos);
  EXPECT_NE(gcode.find("; pen 2 colour: #0050ff"), std::string::npos);
  ASSERT_EQ(run_strand("preview two.gcode --view top -o p.png", dir).exit_code, 0);
  const std::string png = slurp(dir + "/p.png");
  const PxBox legend{0, 0, 180, 20}, drawing{180, 20, 1200, 700};  // swatches top left
  const ColourSpot red = colour_spot(png, 0xd4, 0x00, 0x00, 30, drawing);
  const ColourSpot blue = colour_spot(png, 0x00, 0x50, 0xff, 30, drawing);
  EXPECT_GT(red.count, 200);
  EXPECT_GT(blue.count, 200);
  EXPECT_GT(std::abs(red.y_px - blue.y_px), 100.0) << "each line in its own colour";
  EXPECT_GT(colour_spot(png, 0xd4, 0x00, 0x00, 30, legend).count, 80) << "pen 1's swatch";
  EXPECT_GT(colour_spot(png, 0x00, 0x50, 0xff, 30, legend).count, 80) << "pen 2's swatch";
  ASSERT_EQ(run_strand("preview two.gcode -o p.html", dir).exit_code, 0);
  const std::string html = slurp(dir + "/p.html");
  EXPECT_NE(html.find("\"pen 1 #d40000\""), std::string::npos);
  EXPECT_NE(html.find("\"pen 2 #0050ff\""), std::string::npos);
}

// A file preview cannot read names the input as check does.
TEST(PreviewPerPen, ExpressionErrorNamesTheInputLikeCheck) {
  const auto dir = fresh_dir("preview-ngc");
  std::ofstream(dir + "/x.ngc") << "G0 X0 Y0\nG1 X[1/0] Y1\n";
  const auto check = run_strand("check x.ngc", dir);
  const auto preview = run_strand("preview x.ngc -o p.png", dir);
  expect_input_error(preview, "input = x.ngc: line 2");
  EXPECT_EQ(check.exit_code, 2);
  EXPECT_EQ(preview.err, check.err);
  EXPECT_FALSE(exists(dir + "/p.png"));
}

}  // namespace
}  // namespace strand::testing
