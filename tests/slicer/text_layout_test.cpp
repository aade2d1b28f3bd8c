// Text layout against the font data itself: a string's strokes are the Hershey glyphs
// (read straight from libhersheyfont) scaled and placed at the anchor within 0.01 mm;
// tspan offsets, chunks and transforms; white space; outline fonts; missing fonts; the
// Hershey advance fitted to the named font's (--text-width fit). Text along a <textPath> is
// in text_path_test.cpp.
#include "slicer/text_layout.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "slicer/hershey_font.h"
#include "slicer/input_error.h"
#include "slicer/outline_font.h"
#include "slicer/svg_export.h"
#include "tests/support/text_strokes.h"

namespace strand::slicer {
namespace {

using testing::expect_same_points;
using testing::hershey_expected;
using testing::hershey_text;
using testing::hershey_width;
using testing::svg_doc;
using testing::text_vertices;

TEST(TextLayout, StrokesAreTheHersheyGlyphsAtSizeAndPosition) {
  const auto t = hershey_text("<text x='20' y='50' font-size='12'>Strand 42</text>");
  EXPECT_EQ(t.glyphs, 8);
  EXPECT_EQ(t.shapes.size(), 1u);
  EXPECT_TRUE(t.shapes[0].stroked);
  EXPECT_FALSE(t.shapes[0].filled);
  expect_same_points(text_vertices(t), hershey_expected("Strand 42", "futural", 20, 50, 12));
}

TEST(TextLayout, AnchorsShiftEachChunkByItsWidth) {
  for (const auto& [anchor, factor] :
       std::vector<std::pair<std::string, double>>{{"middle", 0.5}, {"end", 1.0}}) {
    const auto t =
        hershey_text("<text x='100' y='40' font-size='10' text-anchor='" + anchor + "' >AbC</text>",
                     "hershey:rowmans");
    expect_same_points(
        text_vertices(t),
        hershey_expected("AbC", "rowmans", 100 - factor * hershey_width("AbC", "rowmans", 10), 40,
                         10));
  }
}

TEST(TextLayout, TspanOffsetsAndAbsolutePositions) {
  // "ab" at (10, 20); tspan "c" shifted by dx=5 dy=-3; tspan "d" starts a new chunk at x=60
  const auto t = hershey_text(
      "<text x='10' y='20' font-size='8'>ab<tspan dx='5' dy='-3'>c</tspan>"
      "<tspan x='60' y='70' text-anchor='end'>d</tspan></text>");
  std::vector<Vec2> want = hershey_expected("ab", "futural", 10, 20, 8);
  const auto c =
      hershey_expected("c", "futural", 10 + hershey_width("ab", "futural", 8) + 5, 17, 8);
  const auto d = hershey_expected("d", "futural", 60 - hershey_width("d", "futural", 8), 70, 8);
  want.insert(want.end(), c.begin(), c.end());
  want.insert(want.end(), d.begin(), d.end());
  expect_same_points(text_vertices(t), want);
}

TEST(TextLayout, PerCharacterListsAndInheritedFontSize) {
  // x list places each character; font-size comes from the group, tspan scales by 150%
  const auto t = hershey_text(
      "<g style='font-size:10px'><text x='10 30' y='50'>AB<tspan "
      "font-size='150%'>C</tspan></text></g>");
  std::vector<Vec2> want = hershey_expected("A", "futural", 10, 50, 10);
  const auto b = hershey_expected("B", "futural", 30, 50, 10);
  const auto c = hershey_expected("C", "futural", 30 + hershey_width("B", "futural", 10), 50, 15);
  want.insert(want.end(), b.begin(), b.end());
  want.insert(want.end(), c.begin(), c.end());
  expect_same_points(text_vertices(t), want);
}

TEST(TextLayout, TransformsApplyToTheGlyphs) {
  // rotate(90) about the origin then translate: (x, y) -> (100 - y, x)
  const auto t = hershey_text(
      "<g transform='translate(100 0)'><text transform='rotate(90)' x='10' y='5' "
      "font-size='10'>L</text></g>");
  auto want = hershey_expected("L", "futural", 10, 5, 10);
  for (auto& p : want) p = Vec2(100 - p.y(), p.x());
  expect_same_points(text_vertices(t), want);
}

TEST(TextLayout, WhiteSpaceCollapsesAndTrims) {
  const auto d = import_svg(svg_doc("<text x='0' y='10'>\n   two \t  words\n  </text>"), "t.svg");
  ASSERT_EQ(d.texts.size(), 1u);
  std::u32string s;
  for (const auto& c : d.texts[0].chars) s += c.code;
  EXPECT_EQ(s, U"two words");
  const auto p =
      import_svg(svg_doc("<text xml:space='preserve' x='0' y='10'> a  b</text>"), "t.svg");
  s.clear();
  for (const auto& c : p.texts[0].chars) s += c.code;
  EXPECT_EQ(s, U" a  b");
}

TEST(TextLayout, HiddenAndUnpaintedTextDrawsNothing) {
  EXPECT_TRUE(hershey_text("<text x='0' y='10' display='none'>a</text>").shapes.empty());
  EXPECT_TRUE(hershey_text("<text x='0' y='10' fill='none'>a</text>").shapes.empty());
  const auto t = hershey_text("<text x='0' y='10'>a<tspan style='display:none'>bcd</tspan></text>");
  EXPECT_EQ(t.glyphs, 1);
}

TEST(TextLayout, MissingGlyphsAreCounted) {
  const auto t = hershey_text("<text x='0' y='10'>a\u00b5m</text>");  // µ is not in the ASCII fonts
  EXPECT_EQ(t.glyphs, 2);
  EXPECT_EQ(t.missing, 1);
}

TEST(TextLayout, OutlineFontsGiveFilledClosedContours) {
  const auto d = import_svg(
      svg_doc("<text x='10' y='50' font-size='20' font-family='DejaVu Sans'>Ob</text>"), "t.svg");
  const auto t = layout_text(d.texts, {TextMode::Outline, ""});
  ASSERT_EQ(t.shapes.size(), 1u);
  EXPECT_TRUE(t.shapes[0].filled);
  EXPECT_EQ(t.fonts.at(0).rfind("DejaVu Sans", 0), 0u);
  // O and b: two contours each (outside and the counter)
  EXPECT_EQ(t.shapes[0].paths.size(), 4u);
  for (const auto& p : t.shapes[0].paths) EXPECT_TRUE(p.closed);
  // both letters sit on the baseline (O overshoots it a little); b's ascender is 0.76 em
  double top = INFINITY, bottom = -INFINITY;
  for (const auto& p : t.shapes[0].paths) {
    for (const auto& q : flatten(p, 0.001)) {
      top = std::min(top, q.y());
      bottom = std::max(bottom, q.y());
    }
  }
  EXPECT_NEAR(bottom, 50.0, 0.4);
  EXPECT_NEAR(bottom - top, 0.76 * 20, 0.6);
}

TEST(TextLayout, FontsThatAreNotInstalledAreRefused) {
  EXPECT_THROW(hershey_text("<text x='0' y='10'>a</text>", "hershey:nosuchfont"), InputError);
  EXPECT_THROW(hershey_text("<text x='0' y='10'>a</text>", "hershey:../../etc/passwd"), InputError);
  const auto d =
      import_svg(svg_doc("<text x='0' y='10' font-family='No Such Font Family'>a</text>"), "t.svg");
  try {
    layout_text(d.texts, {TextMode::Outline, ""});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("No Such Font Family"), std::string::npos);
  }
  // a list falls back to the next installed family, as CSS does
  const auto l = import_svg(
      svg_doc("<text x='0' y='10' font-family=\"'No Such', DejaVu Serif\">a</text>"), "t.svg");
  EXPECT_EQ(layout_text(l.texts, {TextMode::Outline, ""}).fonts.at(0).rfind("DejaVu Serif", 0), 0u);
}

// Hershey fonts have a 32-unit body: the underline lies 4 units below the baseline, the
// line-through 7 units above it, the overline 24 units above it, across the whole run.
TEST(TextLayout, DecorationsAreStrokesAtTheFontsMetrics) {
  const auto t = hershey_text(
      "<text x='10' y='50' font-size='32' text-decoration='underline'>AB"
      "<tspan text-decoration='line-through overline'>C</tspan></text>");
  ASSERT_EQ(t.shapes.size(), 1u);
  const auto& paths = t.shapes[0].paths;
  const std::size_t glyph_paths =
      hershey_text("<text x='10' y='50' font-size='32'>ABC</text>").shapes[0].paths.size();
  // the glyphs, then one underline under AB and C (C keeps its parent's underline), then
  // C's overline and line-through
  ASSERT_EQ(paths.size(), glyph_paths + 4);
  const double ab = hershey_width("AB", "futural", 32), abc = hershey_width("ABC", "futural", 32);
  const std::vector<std::vector<Vec2>> want = {{{10, 54}, {10 + ab, 54}},
                                               {{10 + ab, 54}, {10 + abc, 54}},
                                               {{10 + ab, 26}, {10 + abc, 26}},
                                               {{10 + ab, 43}, {10 + abc, 43}}};
  for (std::size_t k = 0; k < want.size(); ++k) {
    const SubPath& line = paths[glyph_paths + k];
    ASSERT_EQ(line.pieces.size(), 1u);
    EXPECT_LT((line.start - want[k][0]).norm(), 1e-9) << k;
    EXPECT_LT((line.pieces[0].end() - want[k][1]).norm(), 1e-9) << k;
  }
}

TEST(TextLayout, OutlineUnderlineIsABarBelowTheBaseline) {
  const auto d = import_svg(svg_doc("<text x='10' y='50' font-size='20' font-family='DejaVu Sans' "
                                    "style='text-decoration:underline'>ab</text>"),
                            "t.svg");
  const auto t = layout_text(d.texts, {TextMode::Outline, ""});
  ASSERT_EQ(t.shapes.size(), 1u);
  const SubPath& bar = t.shapes[0].paths.back();
  ASSERT_TRUE(bar.closed);
  const auto pts = flatten(bar, 0.001);
  double top = INFINITY, bottom = -INFINITY, left = INFINITY;
  for (const auto& q : pts)
    top = std::min(top, q.y()), bottom = std::max(bottom, q.y()), left = std::min(left, q.x());
  // at the font's own metrics (FreeType's, from the post table): below the baseline, thin
  const Font f = load_outline_font("DejaVu Sans", "normal", "normal", U"ab");
  const double em = 20 / f.units_per_em;
  EXPECT_LT(f.underline_position, 0.0);
  EXPECT_GT(f.underline_position, -0.2 * f.units_per_em);
  EXPECT_NEAR((top + bottom) / 2, 50 - f.underline_position * em, 1e-9);
  EXPECT_NEAR(bottom - top, f.underline_thickness * em, 1e-9);
  EXPECT_NEAR(left, 10.0, 1e-9);
}

// baseline-shift moves a tspan's glyphs (super: +0.4 em, sub: -0.2 em, lengths, % of the
// font-size) without moving the characters after it.
TEST(TextLayout, BaselineShiftRaisesAndLowersTspans) {
  const auto t = hershey_text(
      "<text x='10' y='50' font-size='10'>A<tspan baseline-shift='super' font-size='5'>2"
      "</tspan>B<tspan baseline-shift='sub'>c</tspan><tspan baseline-shift='-3'>d</tspan>"
      "<tspan baseline-shift='50%'>e<tspan baseline-shift='1'>f</tspan></tspan></text>");
  std::vector<Vec2> want = hershey_expected("A", "futural", 10, 50, 10);
  double x = 10 + hershey_width("A", "futural", 10);
  const auto add = [&](const char* s, double y, double size) {
    const auto g = hershey_expected(s, "futural", x, y, size);
    want.insert(want.end(), g.begin(), g.end());
    x += hershey_width(s, "futural", size);
  };
  add("2", 50 - 0.4 * 5, 5);
  add("B", 50, 10);
  add("c", 50 + 0.2 * 10, 10);
  add("d", 53, 10);
  add("e", 45, 10);
  add("f", 44, 10);  // nested shifts add up
  expect_same_points(
      text_vertices(hershey_text(
          "<text x='10' y='50' font-size='10'>A<tspan baseline-shift='super' font-size='5'>2"
          "</tspan>B<tspan baseline-shift='sub'>c</tspan><tspan baseline-shift='-3'>d</tspan>"
          "<tspan baseline-shift='50%'>e<tspan baseline-shift='1'>f</tspan></tspan></text>")),
      want);
  EXPECT_EQ(t.glyphs, 7);
}

TEST(TextLayout, LetterAndWordSpacingWidenTheAdvance) {
  const auto t = hershey_text(
      "<text x='10' y='50' font-size='10' letter-spacing='2' word-spacing='1em'>A B"
      "<tspan letter-spacing='normal'>CD</tspan></text>");
  std::vector<Vec2> want;
  double x = 10;
  const auto add = [&](const char* s, double extra) {
    const auto g = hershey_expected(s, "futural", x, 50, 10);
    want.insert(want.end(), g.begin(), g.end());
    x += hershey_width(s, "futural", 10) + extra;
  };
  add("A", 2);
  add(" ", 2 + 10);
  add("B", 2);
  add("C", 0);
  add("D", 0);
  expect_same_points(text_vertices(t), want);
}

// A drawing written the way the W3C SVG 1.1 text tests are (text-tspan-01, text-align-01):
// positions in em and %, inherited font sizes, anchors; each glyph within 0.2 mm of the
// position computed by hand.
TEST(TextLayout, W3cStyleFixturePlacesEveryLine) {
  std::ifstream in(std::string(STRAND_SOURCE_DIR) + "/tests/data/text-w3c-style.svg");
  std::stringstream ss;
  ss << in.rdbuf();
  const auto d = import_svg(ss.str(), "text-w3c-style.svg");
  EXPECT_EQ(d.skipped, std::vector<std::string>{});
  const auto t = layout_text(d.texts, {TextMode::Hershey, "hershey:futural"});
  ASSERT_EQ(t.elements, 2);  // the third text is unpainted
  // viewBox 0 0 480 360 on 120 x 90 mm: 0.25 mm per user unit
  const double k = 0.25;
  // line 1: x = 10% (48), y = 2em of 24 (48); "Text" at size 24
  std::vector<Vec2> want = hershey_expected("Text", "futural", 48 * k, 48 * k, 24 * k);
  // line 2: the tspan's size is 150% = 36, its dy="1.5em" of its own size (54) below line 1
  const auto l2 = hershey_expected("Big", "futural", 48 * k, (48 + 54) * k, 36 * k);
  want.insert(want.end(), l2.begin(), l2.end());
  // line 3: text-anchor middle at 50% (240), y = 75% (270), size 24
  const double w3 = hershey_width("mid", "futural", 24 * k);
  const auto l3 = hershey_expected("mid", "futural", 240 * k - w3 / 2, 270 * k, 24 * k);
  want.insert(want.end(), l3.begin(), l3.end());
  const auto got = text_vertices(t);
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < got.size(); ++i) EXPECT_LT((got[i] - want[i]).norm(), 0.2) << i;
}
// --text-width fit: a Hershey line as long as the same line in the font the drawing names
// (futural happens to be about as wide as DejaVu Sans, narrower than DejaVu Sans Mono).
TEST(TextWidth, FitMakesTheHersheyLineAsLongAsTheNamedFont) {
  const std::u32string line = U"Strand plots lettering in DejaVu Sans";
  for (const std::string family : {"DejaVu Sans", "DejaVu Sans Mono", "DejaVu Serif"}) {
    SCOPED_TRACE(family);
    const Font named_font = load_outline_font(family, "normal", "normal", line);
    double named = 0;
    for (char32_t c : line) named += named_font.glyphs.at(c).advance * 10 / named_font.units_per_em;
    const auto width = [&](bool fit) {
      // the same line anchored at its start and at its end: the shift is its width
      const auto x0 = [&](const char* anchor) {
        const auto d = import_svg(
            svg_doc("<text x='150' y='50' font-size='10' font-family='" + family +
                    "' text-anchor='" + std::string(anchor) + "'>" + u32_to_utf8(line) + "</text>"),
            "t.svg");
        TextOptions o{TextMode::Hershey, "hershey:futural"};
        o.fit_width = fit;
        return text_vertices(layout_text(d.texts, o)).front().x();
      };
      return x0("start") - x0("end");
    };
    EXPECT_NEAR(width(true), named, 0.01 * named);
    if (family == "DejaVu Sans Mono") {
      EXPECT_GT(std::abs(width(false) - named), 0.05 * named);
    }
  }
  // only across: the letters keep their height
  const auto d = import_svg(svg_doc("<text x='10' y='50' font-size='10' font-family='DejaVu Sans "
                                    "Mono'>Hd</text>"),
                            "t.svg");
  TextOptions fit{TextMode::Hershey, ""};
  fit.fit_width = true;
  const auto a = text_vertices(layout_text(d.texts, fit));
  const auto b = text_vertices(layout_text(d.texts, {TextMode::Hershey, ""}));
  ASSERT_EQ(a.size(), b.size());
  double moved = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_NEAR(a[i].y(), b[i].y(), 1e-9);
    moved = std::max(moved, std::abs(a[i].x() - b[i].x()));
  }
  EXPECT_GT(moved, 0.1);
  const auto summary = layout_text(d.texts, fit).summary();
  EXPECT_NE(summary.find("(hershey:futural, widths of DejaVu Sans Mono Book)"), std::string::npos)
      << summary;
}

TEST(SvgExport, WrittenTextReadsBackToTheSameStrokes) {
  const auto t = hershey_text("<text x='20' y='50' font-size='12'>Ab</text>");
  const auto back = import_svg(write_svg({{"m2", "label", t.shapes}}, 1.0, 0.3), "back.svg");
  ASSERT_EQ(back.shapes.size(), 1u);
  EXPECT_EQ(back.shapes[0].group_ids, std::vector<std::string>{"m2"});
  EXPECT_EQ(back.shapes[0].layer_labels, std::vector<std::string>{"label"});
  // the page is the text's bounds + 1 mm, so the importer's origin is shifted
  const auto a = text_vertices(t);
  std::vector<Vec2> b;
  for (const auto& p : back.shapes[0].paths) {
    b.push_back(p.start);
    for (const auto& c : p.pieces) b.push_back(c.end());
  }
  ASSERT_EQ(a.size(), b.size());
  const Vec2 shift = b[0] - a[0];
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_LT((b[i] - shift - a[i]).norm(), 1e-3);
}

}  // namespace
}  // namespace strand::slicer