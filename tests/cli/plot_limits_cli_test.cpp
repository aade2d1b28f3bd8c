// `strand plot` and `strand text` on hostile drawings (the issue-10 reproducers): each bound in
// docs/limits.md ends the run with exit code 2, one line naming the bound, and no output file,
// instead of a crash, a hang or gigabytes of memory.
#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "slicer/file_io.h"
#include "slicer/svg_import.h"
#include "tests/support/cli_runner.h"

namespace strand::testing {
namespace {

std::string repeat(const std::string& s, int n) {
  std::string out;
  out.reserve(s.size() * static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) out += s;
  return out;
}

std::string svg(const std::string& body) {
  return "<svg xmlns='http://www.w3.org/2000/svg' xmlns:xlink='http://www.w3.org/1999/xlink' "
         "width='100mm' height='100mm' viewBox='0 0 100 100'>" +
         body + "</svg>";
}

const std::string kLine = "<line x2='5' stroke='black'/>";

std::string nested(const std::string& open, const std::string& close, int n) {
  return svg(repeat(open, n) + kLine + repeat(close, n));
}

// 39 levels, each <use>-ing the previous level twice: 2^39 lines if nothing stopped it.
std::string use_doubling() {
  std::string defs = "<defs><line id='u0' x2='5' stroke='black'/>";
  for (int i = 1; i < 40; ++i) {
    const std::string prev = "#u" + std::to_string(i - 1);
    defs += "<g id='u" + std::to_string(i) + "'><use xlink:href='" + prev + "'/><use xlink:href='" +
            prev + "'/></g>";
  }
  return svg(defs + "</defs><use xlink:href='#u39'/>");
}

// Ten levels of ten references each: 10^10 "lol"s (30 GB) if expanded.
std::string billion_laughs() {
  std::string subset = "<!ENTITY l0 \"lol\">";
  for (int i = 1; i <= 10; ++i) {
    subset += "<!ENTITY l" + std::to_string(i) + " \"" +
              repeat("&l" + std::to_string(i - 1) + ";", 10) + "\">";
  }
  return "<?xml version='1.0'?><!DOCTYPE svg [" + subset + "]>" +
         svg("<text y='10'>&l10;</text>" + kLine);
}

// 150 identical 190 mm squares: each under the 20,000 lines of one fill, 5.7 million points
// together.
std::string many_fills() {
  return svg(repeat("<rect x='5' y='5' width='90' height='90' fill='black'/>", 150));
}

// 10,000 tight cubics: each needs 2^9 points at 0.001 mm.
std::string many_curves() {
  return svg("<path fill='none' stroke='black' d='M0 0" +
             repeat(" c0 90 90 90 90 0 c0 -90 -90 -90 -90 0", 5000) + "'/>");
}

// The drawing is made when its test runs: made at registration, every test process (and the
// test listing) would build tens of megabytes it never uses.
struct Case {
  const char* name;
  std::function<std::string()> svg;
  std::string args;
  std::string must_mention;
};

std::vector<Case> cases() {
  return {
      {"nested_groups", [] { return std::string(nested("<g>", "</g>", 100000)); }, "",
       "<g>: elements nest deeper than 256 levels"},
      {"nested_transforms",
       [] { return std::string(nested("<g transform='translate(0.001 0)'>", "</g>", 10000)); }, "",
       "nest deeper than 256"},
      {"use_doubling", [] { return std::string(use_doubling()); }, "",
       "more than 250000 elements copied by <use>"},
      {"bezier_1e308",
       [] {
         return std::string(svg("<path d='M0 0 C1e308 0 0 10 10 10' stroke='black' fill='none'/>"));
       },
       "", "<path>: a coordinate is 1e+308 mm after transforms (at most 1e+07 mm"},
      {"not_finite",
       [] {
         return std::string(svg(
             "<g transform='scale(1e300)'><path id='far' d='M0 0 L1e300 0' stroke='black'/></g>"));
       },
       "", "<path id=\"far\">: a coordinate is not finite"},
      {"clipper_range",
       [] {
         return std::string(
             svg("<rect width='1e308' height='10' stroke='black' fill='none'/><path d='M0 0 L10 0 "
                 "L10 10 "
                 "Z'/>"));
       },
       "", "<rect>: a coordinate is 1e+308 mm"},
      {"path_1e13_long", [] { return std::string(svg("<path d='M0 0 L1e13 0 L1e13 1e13 Z'/>")); },
       "", "a coordinate is 1e+13 mm"},
      {"far_fill_checked_before_hatching",
       [] { return std::string(svg("<path d='M0 0 L5e6 0 L5e6 5e6 Z'/>")); },
       "--hatch-spacing 0.001", "does not fit"},
      {"tolerance_1e_minus_300", [] { return std::string(svg(kLine)); }, "--tolerance 1e-300",
       "plot.tolerance = 1e-300: must be in [0.001, 5]"},
      {"fills_of_the_whole_drawing", [] { return std::string(many_fills()); },
       "--fit 190x190 --hatch-angle 0 --hatch-spacing 0.01",
       "plot.hatch-spacing: the outlines and fills would draw up to"},
      {"curve_points", [] { return std::string(many_curves()); }, "--tolerance 0.001 --fit 100x100",
       "plot.tolerance = 0.001: the curves would flatten"},
      {"text_chars",
       [] { return std::string(svg("<text y='10'>" + repeat("a", 100001) + "</text>")); }, "",
       "text has more than 100000 characters"},
      {"billion_laughs", [] { return std::string(billion_laughs()); }, "",
       "DTD entities expand to more than 16 MiB (at &l10;)"},
      {"entity_cycle",
       [] {
         return std::string("<!DOCTYPE svg [<!ENTITY a '&b;'><!ENTITY b '&a;'>]>" + svg("&a;"));
       },
       "", "refers to itself"},
      {"markup_count", [] { return std::string(svg(repeat("<g/>", 4000001))); }, "",
       "'<' and '=' (elements and attributes; at most 4000000)"},
      {"path_pieces",
       [] {
         return std::string(svg("<path stroke='black' d='M0 0" + repeat("h1", 2000001) + "'/>"));
       },
       "", "more than 2000000 curve pieces"},
      {"fit_scale", [] { return std::string(svg("<line x2='1e-6' stroke='black'/>")); },
       "--fit 100x100", "plot.fit = 100x100"},
  };
}

class PlotLimits : public ::testing::TestWithParam<Case> {};

TEST_P(PlotLimits, ExitTwoOneLineNoFile) {
  const auto dir = fresh_dir("limits");
  slicer::write_file_atomic(dir + "/in.svg", GetParam().svg());
  const auto r = run_strand(
      "plot in.svg --machine xy-plotter-servo -o out.gcode --report out.json " + GetParam().args,
      dir);
  expect_input_error(r, GetParam().must_mention);
  EXPECT_FALSE(exists(dir + "/out.gcode"));
  EXPECT_FALSE(exists(dir + "/out.json"));
}

INSTANTIATE_TEST_SUITE_P(Reproducers, PlotLimits, ::testing::ValuesIn(cases()),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(TextLimits, LongStringsAreRefusedBeforeLayout) {
  const auto dir = fresh_dir("text-limits");
  const std::string many(slicer::kMaxSvgTextChars + 1, 'x');
  expect_input_error(run_strand("text " + many + " -o x.svg", dir),
                     "text: the string has 100001 characters");
  EXPECT_FALSE(exists(dir + "/x.svg"));
  EXPECT_EQ(run_strand("text " + many.substr(0, 2000) + " -o ok.svg", dir).exit_code, 0);
}

// The bounds leave room for real drawings: exactly at a limit still plots.
TEST(PlotLimits, DrawingsJustInsideTheBoundsPlot) {
  const auto dir = fresh_dir("limits-ok");
  slicer::write_file_atomic(dir + "/deep.svg", nested("<g>", "</g>", slicer::kMaxSvgDepth - 2));
  const auto deep = run_strand("plot deep.svg --machine xy-plotter-servo -o deep.gcode", dir);
  EXPECT_EQ(deep.exit_code, 0) << deep.err;
  slicer::write_file_atomic(
      dir + "/fills.svg",
      svg(repeat("<rect x='5' y='5' width='90' height='90' fill='black'/>", 10)));
  const auto fills = run_strand(
      "plot fills.svg --machine xy-plotter-servo --fit 190x190 --hatch-angle 0 --hatch-spacing 0.1 "
      "-o fills.gcode",
      dir);
  EXPECT_EQ(fills.exit_code, 0) << fills.err;
}

}  // namespace
}  // namespace strand::testing
