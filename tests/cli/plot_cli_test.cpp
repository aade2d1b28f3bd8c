// `strand plot` from the outside: every sample on every plotter, the end-to-end error bound
// checked through the forward kinematics, ordering gains, determinism, the drum rule, erase
// sweeps, and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>

#include "machines/pen_emitter.h"
#include "machines/plotter_kinematics.h"
#include "machines/profile.h"
#include "postprocess/inspect/gcode_parser.h"
#include "slicer/file_io.h"
#include "slicer/svg_import.h"
#include "tests/support/cli_runner.h"

namespace strand::testing {
namespace {

const std::string kSamples = std::string(STRAND_SOURCE_DIR) + "/samples/plot/";
const char* kPlotters[] = {"xy-plotter-servo", "xy-plotter-z", "xy-plotter-grbl", "polargraph",
                           "polar-rtheta", "wall-drum-4pen"};

struct SampleCase {
  const char* svg;
  const char* machine;
};

class EverySample : public ::testing::TestWithParam<SampleCase> {};

TEST_P(EverySample, PlotsAndParsesBackAsPenMoves) {
  const auto dir = fresh_dir("plot");
  const auto r = run_strand("plot '" + kSamples + GetParam().svg + "' --machine " + GetParam().machine +
                            " --fit 180x120 -o out.gcode --report out.json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto parsed = post::parse_gcode(slurp(dir + "/out.gcode"));
  EXPECT_FALSE(parsed.has_e);
  int draws = 0;
  for (const auto& mv : parsed.program.moves) draws += mv.kind == slicer::MoveKind::Deposit;
  EXPECT_GT(draws, 10);
  const auto report = nlohmann::json::parse(slurp(dir + "/out.json"));
  EXPECT_LE(report["pen_up_after_ordering"]["pen_up_mm"].get<double>(),
            report["pen_up_before_ordering"]["pen_up_mm"].get<double>() + 1e-9);
}

std::vector<SampleCase> all_cases() {
  std::vector<SampleCase> out;
  for (const char* svg : {"shapes.svg", "layers.svg", "lines.svg"}) {
    for (const char* m : kPlotters) out.push_back({svg, m});
  }
  return out;
}

INSTANTIATE_TEST_SUITE_P(Plotters, EverySample, ::testing::ValuesIn(all_cases()),
                         [](const auto& info) {
                           std::string n = std::string(info.param.svg) + "_" + info.param.machine;
                           for (char& c : n) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
                           return n;
                         });

// A 100 mm square with a circle of radius 40 inside, centred: the square makes centring exact.
const char* kCircleInSquare =
    "<svg xmlns='http://www.w3.org/2000/svg' width='100mm' height='100mm' viewBox='0 0 100 100' "
    "fill='none' stroke='black'><rect width='100' height='100'/><circle cx='50' cy='50' r='40'/></svg>";

struct BoundCase {
  const char* machine;
  double scale;
  double tolerance;
};

class EndToEnd : public ::testing::TestWithParam<BoundCase> {};

TEST_P(EndToEnd, EmittedMovesStayWithinToleranceOfTheTrueShapes) {
  const auto dir = fresh_dir("bound");
  slicer::write_file_atomic(dir + "/c.svg", kCircleInSquare);
  const auto& p = GetParam();
  const auto r = run_strand("plot c.svg --machine " + std::string(p.machine) + " --scale " + std::to_string(p.scale) +
                            " --tolerance " + std::to_string(p.tolerance) + " -o c.gcode --report c.json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto m = machines::load_profile(p.machine);
  const auto report = nlohmann::json::parse(slurp(dir + "/c.json"));
  const auto& area = report["drawable_area_mm"];
  const slicer::Vec2 c((area[0][0].get<double>() + area[1][0].get<double>()) / 2,
                       (area[0][1].get<double>() + area[1][1].get<double>()) / 2);
  const double radius = 40 * p.scale, half = 50 * p.scale;
  const auto shape_distance = [&](const slicer::Vec2& q) {
    const slicer::Vec2 d = (q - c).cwiseAbs();
    const double to_square = std::max(d.x(), d.y()) <= half
                                 ? half - std::max(d.x(), d.y())
                                 : (d - slicer::Vec2(half, half)).cwiseMax(0.0).norm();
    return std::min(std::abs((q - c).norm() - radius), to_square);
  };
  const auto parsed = post::parse_gcode(slurp(dir + "/c.gcode"));
  slicer::Vec2 from = parsed.program.start_mm.head<2>();
  double worst = 0.0;
  int samples = 0;
  for (const auto& mv : parsed.program.moves) {
    const slicer::Vec2 to = mv.end_mm.head<2>();
    if (mv.kind == slicer::MoveKind::Deposit) {
      for (int k = 0; k <= 16; ++k, ++samples) {
        worst = std::max(worst, shape_distance(machines::to_paper(m.plotter.setup, from + (to - from) * (k / 16.0))));
      }
    }
    if (mv.kind == slicer::MoveKind::Travel || mv.kind == slicer::MoveKind::Deposit) from = to;
  }
  EXPECT_GT(samples, 1000);
  EXPECT_LE(worst, p.tolerance);
}

INSTANTIATE_TEST_SUITE_P(Plotters, EndToEnd,
                         ::testing::Values(BoundCase{"xy-plotter-servo", 2.5, 0.05},
                                           BoundCase{"polargraph", 3.0, 0.05},
                                           BoundCase{"polargraph", 3.0, 0.1},
                                           BoundCase{"polar-rtheta", 2.0, 0.05},
                                           BoundCase{"wall-drum-4pen", 5.0, 0.05}));

TEST(PlotCli, SameInputGivesIdenticalBytes) {
  const auto dir = fresh_dir("det");
  const std::string args = "plot '" + kSamples + "shapes.svg' --machine wall-drum-4pen --fit 600x400 ";
  ASSERT_EQ(run_strand(args + "-o a.gcode --report a.json", dir).exit_code, 0);
  ASSERT_EQ(run_strand(args + "-o b.gcode --report b.json", dir).exit_code, 0);
  EXPECT_EQ(slurp(dir + "/a.gcode"), slurp(dir + "/b.gcode"));
}

TEST(PlotCli, OrderingCutsPenUpTravelOnScrambledLines) {
  const auto dir = fresh_dir("order");
  const std::string args = "plot '" + kSamples + "lines.svg' --machine xy-plotter-servo ";
  ASSERT_EQ(run_strand(args + "-o a.gcode --report a.json", dir).exit_code, 0);
  ASSERT_EQ(run_strand(args + "--no-order -o b.gcode --report b.json", dir).exit_code, 0);
  const auto a = nlohmann::json::parse(slurp(dir + "/a.json"));
  const auto b = nlohmann::json::parse(slurp(dir + "/b.json"));
  EXPECT_LT(a["estimate"]["pen_up_mm"].get<double>(), 0.3 * b["estimate"]["pen_up_mm"].get<double>());
  EXPECT_NEAR(a["estimate"]["draw_mm"].get<double>(), b["estimate"]["draw_mm"].get<double>(), 1e-6);
}

// The drum may turn back only to engage (engage -> rest) or to write (rest -> write).
TEST(PlotCli, DrumNeverTurnsBackWithAMarkerEngaged) {
  const auto dir = fresh_dir("drum");
  // pens used out of order in the document: 3, 1, 4, 2
  slicer::write_file_atomic(dir + "/d.svg",
      "<svg xmlns='http://www.w3.org/2000/svg' width='300mm' height='100mm' viewBox='0 0 300 100' stroke='black' fill='none'>"
      "<g id='m3'><line x1='0' y1='0' x2='50' y2='50'/></g><g id='m1'><line x1='60' y1='0' x2='110' y2='50'/></g>"
      "<g id='m4'><line x1='120' y1='0' x2='170' y2='50'/></g><g id='m2'><line x1='180' y1='0' x2='230' y2='50'/></g></svg>");
  ASSERT_EQ(run_strand("plot d.svg --machine wall-drum-4pen --no-order -o d.gcode", dir).exit_code, 0);
  const auto m = machines::load_profile("wall-drum-4pen");
  const auto& pen = m.plotter.pen;
  std::istringstream in(slurp(dir + "/d.gcode"));
  std::string line, prev_line;
  double z = 0.0;
  int backwards = 0, resets = 0;
  const std::regex zword(R"(^G1 Z(-?[0-9.]+))");
  std::smatch mz;
  while (std::getline(in, line)) {
    if (line.rfind("G92 Z0", 0) == 0) {
      z = 0.0;
      ++resets;
    }
    if (std::regex_search(line, mz, zword)) {
      const double nz = std::stod(mz[1]);
      EXPECT_EQ(std::getline(in, prev_line) ? prev_line : "", "M400") << "after " << line;
      if (nz < z - 1e-9) {
        bool allowed = false;
        for (int k = 1; k <= pen.count; ++k) {
          allowed = allowed || (std::abs(z - machines::drum_engage_deg(pen, k)) < 1e-6 && std::abs(nz - machines::drum_rest_deg(pen, k)) < 1e-6) ||
                    (std::abs(z - machines::drum_rest_deg(pen, k)) < 1e-6 && std::abs(nz - machines::drum_write_deg(pen, k)) < 1e-6);
        }
        EXPECT_TRUE(allowed) << "drum turns back from " << z << " to " << nz;
        ++backwards;
      }
      z = nz;
    }
  }
  EXPECT_EQ(resets, 1 + 2);  // the start, then full turns for 3 -> 1 and 4 -> 2
  EXPECT_GE(backwards, 8);   // 4 engagements and 4 pen drops
}

TEST(PlotCli, EraseSweepsCoverTheDrawingWithDwells) {
  const auto dir = fresh_dir("erase");
  const auto r = run_strand("plot '" + kSamples + "layers.svg' --machine wall-drum-4pen --fit 300x200 -o w.gcode --erase w_erase.gcode", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string e = slurp(dir + "/w_erase.gcode");
  EXPECT_NE(e.find("M109 S180"), std::string::npos);
  EXPECT_NE(e.find("G4 P3000"), std::string::npos);
  // 200 mm tall at a 20 mm disc: 10 rows, each heated once
  std::size_t rows = 0;
  for (std::size_t at = e.find("M109"); at != std::string::npos; at = e.find("M109", at + 1)) ++rows;
  EXPECT_EQ(rows, 10u);
}

struct BadCase {
  const char* name;
  const char* svg;
  const char* args;
  const char* must_mention;
};


// Issue 5: `strand check`, pen-aware, passes on every sample drawing for every plotter.
TEST(PlotCli, EverySamplePassesCheckOnEveryPlotter) {
  const auto dir = fresh_dir("plotcheck");
  for (const char* machine : {"xy-plotter-servo", "xy-plotter-z", "xy-plotter-grbl", "polargraph",
                              "polar-rtheta", "wall-drum-4pen"}) {
    for (const char* svg : {"shapes", "layers", "lines"}) {
      SCOPED_TRACE(std::string(machine) + " " + svg);
      const auto plot = run_strand("plot '" + kSamples + svg + ".svg' --machine " + machine +
                                       " --fit 200x150 -o p.gcode", dir);
      ASSERT_EQ(plot.exit_code, 0) << plot.err;
      const auto check = run_strand(std::string("check p.gcode --json --machine ") + machine, dir);
      EXPECT_EQ(check.exit_code, 0) << check.out;
      EXPECT_NE(check.out.find("\"pen_drawing\": true"), std::string::npos) << check.out.substr(0, 300);
    }
  }
}

// Issue 14: text is drawn by default and counted; --text none keeps it skipped.
TEST(PlotCli, TextIsDrawnAndCountedOrSkippedWithTextNone) {
  const auto dir = fresh_dir("plottext");
  slicer::write_file_atomic(dir + "/t.svg",
      "<svg xmlns='http://www.w3.org/2000/svg' width='100mm' height='50mm' viewBox='0 0 100 50'>"
      "<rect width='100' height='50' fill='none' stroke='black'/><text x='10' y='30' font-size='10'>AB</text></svg>");
  const auto drawn = run_strand("plot t.svg -o a.gcode --report a.json", dir);
  ASSERT_EQ(drawn.exit_code, 0) << drawn.err;
  EXPECT_NE(drawn.out.find("text           1 element(s), 2 glyphs (hershey:futural)"), std::string::npos) << drawn.out;
  const auto skipped = run_strand("plot t.svg --text none -o b.gcode --report b.json", dir);
  ASSERT_EQ(skipped.exit_code, 0) << skipped.err;
  EXPECT_NE(skipped.out.find("skipped        text (1)"), std::string::npos) << skipped.out;
  const auto a = nlohmann::json::parse(slurp(dir + "/a.json"));
  const auto b = nlohmann::json::parse(slurp(dir + "/b.json"));
  // A: 3 strokes, B: 2 strokes; both letters add pen-down length
  EXPECT_GT(a["estimate"]["draw_mm"].get<double>(), b["estimate"]["draw_mm"].get<double>() + 20.0);
  EXPECT_EQ(b["skipped_elements"], nlohmann::json::array({"text (1)"}));
}

// Issue 19: text along a <textPath> plots, passes check, and its strokes stand on the ring
// it follows (capitals: from the ring out to 21/32 of the font size).
TEST(PlotCli, TextOnAPathStandsOnItsRingAndPassesCheck) {
  const auto dir = fresh_dir("textpath");
  slicer::write_file_atomic(dir + "/p.svg",
      "<svg xmlns='http://www.w3.org/2000/svg' xmlns:xlink='http://www.w3.org/1999/xlink' width='100mm' "
      "height='100mm' viewBox='0 0 100 100'><defs><path id='ring' d='M 10 50 A 40 40 0 1 1 90 50 A 40 40 0 1 1 10 50'/>"
      "</defs><rect width='100' height='100' fill='none' stroke='black'/><text font-size='8' text-anchor='middle'>"
      "<textPath xlink:href='#ring' startOffset='25%'>PLOTTED ON A RING</textPath></text></svg>");
  const auto plot = run_strand("plot p.svg -o p.gcode --report p.json", dir);
  ASSERT_EQ(plot.exit_code, 0) << plot.err;
  EXPECT_NE(plot.out.find("text           1 element(s), 14 glyphs (hershey:futural)"), std::string::npos) << plot.out;
  EXPECT_EQ(run_strand("check p.gcode --machine xy-plotter-servo", dir).exit_code, 0);
  const auto m = machines::load_profile("xy-plotter-servo");
  const auto report = nlohmann::json::parse(slurp(dir + "/p.json"));
  const auto& area = report["drawable_area_mm"];
  const slicer::Vec2 c((area[0][0].get<double>() + area[1][0].get<double>()) / 2,
                       (area[0][1].get<double>() + area[1][1].get<double>()) / 2);
  const auto parsed = post::parse_gcode(slurp(dir + "/p.gcode"));
  slicer::Vec2 from = parsed.program.start_mm.head<2>();
  int on_ring = 0, upper = 0;
  for (const auto& mv : parsed.program.moves) {
    const slicer::Vec2 to = mv.end_mm.head<2>();
    if (mv.kind == slicer::MoveKind::Deposit) {
      for (double k : {0.0, 0.5, 1.0}) {
        const slicer::Vec2 q = machines::to_paper(m.plotter.setup, from + (to - from) * k) - c;
        if (std::abs(std::max(std::abs(q.x()), std::abs(q.y())) - 50) < 0.05) continue;  // the square
        const double r = q.norm();
        EXPECT_GT(r, 40 - 0.3) << q.transpose();
        EXPECT_LT(r, 40 + 21.0 / 32 * 8 + 0.3) << q.transpose();
        ++on_ring;
        upper += q.y() > 0;  // centred on the top of the ring (paper y up)
      }
    }
    if (mv.kind == slicer::MoveKind::Travel || mv.kind == slicer::MoveKind::Deposit) from = to;
  }
  EXPECT_GT(on_ring, 100);
  EXPECT_EQ(upper, on_ring);
}

TEST(TextCli, WritesAnSvgThatPlotsAndGcodeDirectly) {
  const auto dir = fresh_dir("textcli");
  const auto svg = run_strand("text 'd=0.84\\nl=1.6' --size 6 -o label.svg", dir);
  ASSERT_EQ(svg.exit_code, 0) << svg.err;
  EXPECT_NE(svg.out.find("11 glyphs (hershey:futural)"), std::string::npos) << svg.out;
  const auto plot = run_strand("plot label.svg -o label.gcode", dir);
  ASSERT_EQ(plot.exit_code, 0) << plot.err;
  const auto direct = run_strand("text 'd=0.84\\nl=1.6' --size 6 -o direct.gcode --report direct.json", dir);
  ASSERT_EQ(direct.exit_code, 0) << direct.err;
  const auto report = nlohmann::json::parse(slurp(dir + "/direct.json"));
  // two lines 1.25 em apart: about 6 mm of cap height plus 7.5 mm between baselines
  EXPECT_NEAR(report["estimate"]["size_mm"][1].get<double>(), 0.66 * 6 + 7.5, 1.0);
  EXPECT_EQ(run_strand("text x --font 'No Such Face' -o x.svg", dir).exit_code, 2);
  EXPECT_FALSE(exists(dir + "/x.svg"));
  expect_input_error(run_strand("text x -o x.pdf", dir), "text.output");
}

// Issue 14: a grey photo traced into two pen layers, level k on pen k, cross-hatched.
TEST(TraceCli, PhotoTracesIntoTwoPenLayers) {
  const auto dir = fresh_dir("trace");
  const auto svg = run_strand("trace '" + kSamples + "photo.png' --levels 2 -o photo.svg", dir);
  ASSERT_EQ(svg.exit_code, 0) << svg.err;
  const auto d = slicer::import_svg(slurp(dir + "/photo.svg"), "photo.svg");
  ASSERT_GE(d.shapes.size(), 2u);
  EXPECT_EQ(d.shapes.front().group_ids, std::vector<std::string>{"m1"});
  EXPECT_EQ(d.shapes.back().group_ids, std::vector<std::string>{"m2"});
  EXPECT_LT((d.page_mm - slicer::Vec2(60, 40)).norm(), 1e-9);  // 240 x 160 px at 0.25 mm
  const auto plot = run_strand("plot '" + kSamples + "photo.png' --trace --levels 2 --hatch-spacing 1.5 -o p.gcode --report p.json", dir);
  ASSERT_EQ(plot.exit_code, 0) << plot.err;
  const std::string g = slurp(dir + "/p.gcode");
  EXPECT_NE(g.find(";PEN:1"), std::string::npos);
  EXPECT_NE(g.find(";PEN:2"), std::string::npos);
  const auto report = nlohmann::json::parse(slurp(dir + "/p.json"));
  EXPECT_GT(report["estimate"]["draw_mm_per_pen"][0].get<double>(), report["estimate"]["draw_mm_per_pen"][1].get<double>());
  EXPECT_EQ(run_strand("check p.gcode --machine xy-plotter-servo", dir).exit_code, 0);
}

TEST(TraceCli, BadImagesAndOptionsAreInputErrors) {
  const auto dir = fresh_dir("tracebad");
  slicer::write_file_atomic(dir + "/x.png", "not a png at all");
  expect_input_error(run_strand("trace x.png -o x.svg", dir), "not an image");
  expect_input_error(run_strand("plot x.png --trace -o x.gcode", dir), "not an image");
  expect_input_error(run_strand("trace '" + kSamples + "photo.png' --levels 9 -o x.svg", dir), "trace.levels");
  expect_input_error(run_strand("plot '" + kSamples + "shapes.svg' --levels 2 -o x.gcode", dir), "--trace");
  EXPECT_FALSE(exists(dir + "/x.svg"));
  EXPECT_FALSE(exists(dir + "/x.gcode"));
}

// Issue 19: an unevenly lit scan (samples/plot/uneven-page.pgm) traces to its six letters
// (3 bars, 3 rings with their counters) with mkbitmap's filters or an adaptive threshold.
TEST(TraceCli, HighPassAndAdaptiveThresholdTraceAnUnevenPageToLetters) {
  const auto dir = fresh_dir("traceuneven");
  const std::string page = "'" + kSamples + "uneven-page.pgm'";
  for (const std::string flags : {"--highpass 8 --upscale 2", "--threshold adaptive"}) {
    const auto r = run_strand("trace " + page + " " + flags + " --pixel-size 1 -o page.svg", dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find(": 9 outline(s), 240 x 120 px"), std::string::npos) << flags << "\n" << r.out;
  }
  expect_input_error(run_strand("trace " + page + " --threshold bright -o x.svg", dir),
                     "trace.threshold = bright: must be a grey in (0, 1] or adaptive");
  expect_input_error(run_strand("trace " + page + " --upscale 9 -o x.svg", dir), "trace.upscale");
  expect_input_error(run_strand("trace " + page + " --highpass -1 -o x.svg", dir), "trace.highpass");
  EXPECT_FALSE(exists(dir + "/x.svg"));
}

// Issue 19: valid SVG that stopped the whole plot (dy="1em", x="50%", font-size="inherit")
// plots, and an Illustrator sheet's classes make outlined boxes and connector strokes.
TEST(PlotCli, RelativeLengthsAndIllustratorStyleSheetsPlot) {
  const auto dir = fresh_dir("plotcss");
  slicer::write_file_atomic(dir + "/w3c.svg",
                            "<svg xmlns='http://www.w3.org/2000/svg' width='100mm' height='50mm' viewBox='0 0 100 50'>"
                            "<text x='50%' y='20' font-size='inherit'>A<tspan dy='1em'>b</tspan></text>"
                            "<rect width='3q' height='4'/><line x2='10' stroke='black'/></svg>");
  const auto none = run_strand("plot w3c.svg --text none -o a.gcode", dir);
  ASSERT_EQ(none.exit_code, 0) << none.err;
  EXPECT_NE(none.out.find("<rect> width = \"3q\": not a length (element skipped) (1)"), std::string::npos) << none.out;
  ASSERT_EQ(run_strand("plot w3c.svg -o b.gcode", dir).exit_code, 0);
  const auto css = run_strand("plot '" + kSamples + "illustrator_css.svg' -o c.gcode --report c.json", dir);
  ASSERT_EQ(css.exit_code, 0) << css.err;
  const auto report = nlohmann::json::parse(slurp(dir + "/c.json"));
  EXPECT_EQ(report["skipped_elements"], nlohmann::json::array());
}

TEST(PlotCli, ConcentricFillsPassCheckOnEveryPlotter) {
  const auto dir = fresh_dir("concentric");
  for (const char* machine : kPlotters) {
    SCOPED_TRACE(machine);
    const auto r = run_strand("plot '" + kSamples + "lettering.svg' --machine " + std::string(machine) +
                              " --fit 200x120 --fill concentric --hatch-spacing 1.5 -o c.gcode", dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(run_strand(std::string("check c.gcode --machine ") + machine, dir).exit_code, 0);
  }
}

class PlotBadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(PlotBadInput, ExitTwoOneLineNoFile) {
  const auto dir = fresh_dir("bad");
  slicer::write_file_atomic(dir + "/in.svg", GetParam().svg);
  const auto r = run_strand(std::string("plot in.svg -o out.gcode --report out.json ") + GetParam().args, dir);
  expect_input_error(r, GetParam().must_mention);
  EXPECT_FALSE(exists(dir + "/out.gcode"));
  EXPECT_FALSE(exists(dir + "/out.json"));
}

const char* kLine = "<svg xmlns='http://www.w3.org/2000/svg' width='100mm' height='100mm' viewBox='0 0 100 100'><g id='m3'><line x2='100' y2='100' stroke='black'/></g></svg>";

INSTANTIATE_TEST_SUITE_P(
    Cases, PlotBadInput,
    ::testing::Values(
        BadCase{"malformed_xml", "<svg><g></svg>", "", "malformed XML"},
        BadCase{"nothing_drawable", "<svg xmlns='http://www.w3.org/2000/svg' width='10' height='10'><text>x</text></svg>", "--text none", "nothing drawable"},
        BadCase{"hershey_font_missing", "<svg xmlns='http://www.w3.org/2000/svg' width='10' height='10'><text>x</text></svg>", "--font hershey:nosuch", "hershey:nosuch"},
        BadCase{"outline_font_missing", "<svg xmlns='http://www.w3.org/2000/svg' width='10' height='10'><text font-family='No Such Face'>x</text></svg>", "--text outline", "No Such Face"},
        BadCase{"bad_fill", kLine, "--fill zigzag", "plot.fill"},
        BadCase{"bad_hatch_spacing", kLine, "--hatch-spacing 0", "plot.hatch-spacing"},
        BadCase{"unknown_units", "<svg xmlns='http://www.w3.org/2000/svg' width='10furlong' height='10'/>", "", "unknown unit"},
        BadCase{"does_not_fit", kLine, "--scale 10", "does not fit"},
        BadCase{"outside_polargraph_area", kLine, "--machine polargraph --scale 2 --offset 0,-450", "tension"},
        BadCase{"pen_machine_lacks", kLine, "--pens m3=7", "pen 7"},
        BadCase{"not_a_plotter", kLine, "--machine marlin-xyz-200", "not a plotter"},
        BadCase{"bad_tolerance", kLine, "--tolerance 0.0001", "tolerance"}),
    [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace strand::testing
