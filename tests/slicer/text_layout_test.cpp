// Text layout against the font data itself: a string's strokes are the Hershey glyphs
// (read straight from libhersheyfont) scaled and placed at the anchor within 0.01 mm;
// tspan offsets, chunks and transforms; white space; outline fonts; missing fonts; text
// along a <textPath> (glyphs on a circle, startOffset, anchors, the end of the path); the
// Hershey advance fitted to the named font's (--text-width fit).
#include "slicer/text_layout.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

extern "C" {
#include <hersheyfont.h>
}

#include "slicer/hershey_font.h"
#include "slicer/input_error.h"
#include "slicer/outline_font.h"
#include "slicer/svg_export.h"

namespace strand::slicer {
namespace {

std::string doc(const std::string& body) {
  return "<svg xmlns='http://www.w3.org/2000/svg' width='200mm' height='100mm' viewBox='0 0 200 "
         "100'>" +
         body + "</svg>";
}

TextDrawing hershey(const std::string& body, const std::string& font = "hershey:futural") {
  return layout_text(import_svg(doc(body), "t.svg").texts, {TextMode::Hershey, font});
}

// Every vertex of the layout, in order.
std::vector<Vec2> vertices(const TextDrawing& t) {
  std::vector<Vec2> out;
  for (const auto& s : t.shapes) {
    for (const auto& p : s.paths) {
      out.push_back(p.start);
      for (const auto& c : p.pieces) out.push_back(c.end());
    }
  }
  return out;
}

// The same string laid out by hand from libhersheyfont's raw glyphs: pen at (x0, y0) in
// mm, size in mm, SVG y down.
std::vector<Vec2> expected(const std::string& s, const char* font, double x0, double y0,
                           double size) {
  hershey_font* f = hershey_font_load(font);
  EXPECT_NE(f, nullptr);
  std::vector<Vec2> out;
  const double k = size / 32.0;
  double x = x0;
  for (unsigned char ch : s) {
    const hershey_glyph* g = hershey_font_glyph(f, ch);
    for (const hershey_path* p = g->paths; p; p = p->next) {
      if (p->nverts < 2) continue;
      for (int i = 0; i < p->nverts; ++i)
        out.emplace_back(x + p->verts[i].x * k, y0 - p->verts[i].y * k);
    }
    x += g->width * k;
  }
  hershey_font_free(f);
  return out;
}

void expect_same(const std::vector<Vec2>& got, const std::vector<Vec2>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < got.size(); ++i) EXPECT_LT((got[i] - want[i]).norm(), 0.01) << i;
}

double width_of(const std::string& s, const char* font, double size) {
  hershey_font* f = hershey_font_load(font);
  double w = 0;
  for (unsigned char ch : s) w += hershey_font_glyph(f, ch)->width;
  hershey_font_free(f);
  return w * size / 32.0;
}

TEST(TextLayout, StrokesAreTheHersheyGlyphsAtSizeAndPosition) {
  const auto t = hershey("<text x='20' y='50' font-size='12'>Strand 42</text>");
  EXPECT_EQ(t.glyphs, 8);
  EXPECT_EQ(t.shapes.size(), 1u);
  EXPECT_TRUE(t.shapes[0].stroked);
  EXPECT_FALSE(t.shapes[0].filled);
  expect_same(vertices(t), expected("Strand 42", "futural", 20, 50, 12));
}

TEST(TextLayout, AnchorsShiftEachChunkByItsWidth) {
  for (const auto& [anchor, factor] :
       std::vector<std::pair<std::string, double>>{{"middle", 0.5}, {"end", 1.0}}) {
    const auto t =
        hershey("<text x='100' y='40' font-size='10' text-anchor='" + anchor + "' >AbC</text>",
                "hershey:rowmans");
    expect_same(vertices(t),
                expected("AbC", "rowmans", 100 - factor * width_of("AbC", "rowmans", 10), 40, 10));
  }
}

TEST(TextLayout, TspanOffsetsAndAbsolutePositions) {
  // "ab" at (10, 20); tspan "c" shifted by dx=5 dy=-3; tspan "d" starts a new chunk at x=60
  const auto t = hershey(
      "<text x='10' y='20' font-size='8'>ab<tspan dx='5' dy='-3'>c</tspan>"
      "<tspan x='60' y='70' text-anchor='end'>d</tspan></text>");
  std::vector<Vec2> want = expected("ab", "futural", 10, 20, 8);
  const auto c = expected("c", "futural", 10 + width_of("ab", "futural", 8) + 5, 17, 8);
  const auto d = expected("d", "futural", 60 - width_of("d", "futural", 8), 70, 8);
  want.insert(want.end(), c.begin(), c.end());
  want.insert(want.end(), d.begin(), d.end());
  expect_same(vertices(t), want);
}

TEST(TextLayout, PerCharacterListsAndInheritedFontSize) {
  // x list places each character; font-size comes from the group, tspan scales by 150%
  const auto t = hershey(
      "<g style='font-size:10px'><text x='10 30' y='50'>AB<tspan "
      "font-size='150%'>C</tspan></text></g>");
  std::vector<Vec2> want = expected("A", "futural", 10, 50, 10);
  const auto b = expected("B", "futural", 30, 50, 10);
  const auto c = expected("C", "futural", 30 + width_of("B", "futural", 10), 50, 15);
  want.insert(want.end(), b.begin(), b.end());
  want.insert(want.end(), c.begin(), c.end());
  expect_same(vertices(t), want);
}

TEST(TextLayout, TransformsApplyToTheGlyphs) {
  // rotate(90) about the origin then translate: (x, y) -> (100 - y, x)
  const auto t = hershey(
      "<g transform='translate(100 0)'><text transform='rotate(90)' x='10' y='5' "
      "font-size='10'>L</text></g>");
  auto want = expected("L", "futural", 10, 5, 10);
  for (auto& p : want) p = Vec2(100 - p.y(), p.x());
  expect_same(vertices(t), want);
}

TEST(TextLayout, WhiteSpaceCollapsesAndTrims) {
  const auto d = import_svg(doc("<text x='0' y='10'>\n   two \t  words\n  </text>"), "t.svg");
  ASSERT_EQ(d.texts.size(), 1u);
  std::u32string s;
  for (const auto& c : d.texts[0].chars) s += c.code;
  EXPECT_EQ(s, U"two words");
  const auto p = import_svg(doc("<text xml:space='preserve' x='0' y='10'> a  b</text>"), "t.svg");
  s.clear();
  for (const auto& c : p.texts[0].chars) s += c.code;
  EXPECT_EQ(s, U" a  b");
}

TEST(TextLayout, HiddenAndUnpaintedTextDrawsNothing) {
  EXPECT_TRUE(hershey("<text x='0' y='10' display='none'>a</text>").shapes.empty());
  EXPECT_TRUE(hershey("<text x='0' y='10' fill='none'>a</text>").shapes.empty());
  const auto t = hershey("<text x='0' y='10'>a<tspan style='display:none'>bcd</tspan></text>");
  EXPECT_EQ(t.glyphs, 1);
}

TEST(TextLayout, MissingGlyphsAreCounted) {
  const auto t = hershey("<text x='0' y='10'>a\u00b5m</text>");  // µ is not in the ASCII fonts
  EXPECT_EQ(t.glyphs, 2);
  EXPECT_EQ(t.missing, 1);
}

TEST(TextLayout, OutlineFontsGiveFilledClosedContours) {
  const auto d = import_svg(
      doc("<text x='10' y='50' font-size='20' font-family='DejaVu Sans'>Ob</text>"), "t.svg");
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
  EXPECT_THROW(hershey("<text x='0' y='10'>a</text>", "hershey:nosuchfont"), InputError);
  EXPECT_THROW(hershey("<text x='0' y='10'>a</text>", "hershey:../../etc/passwd"), InputError);
  const auto d =
      import_svg(doc("<text x='0' y='10' font-family='No Such Font Family'>a</text>"), "t.svg");
  try {
    layout_text(d.texts, {TextMode::Outline, ""});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("No Such Font Family"), std::string::npos);
  }
  // a list falls back to the next installed family, as CSS does
  const auto l = import_svg(
      doc("<text x='0' y='10' font-family=\"'No Such', DejaVu Serif\">a</text>"), "t.svg");
  EXPECT_EQ(layout_text(l.texts, {TextMode::Outline, ""}).fonts.at(0).rfind("DejaVu Serif", 0), 0u);
}

// Hershey fonts have a 32-unit body: the underline lies 4 units below the baseline, the
// line-through 7 units above it, the overline 24 units above it, across the whole run.
TEST(TextLayout, DecorationsAreStrokesAtTheFontsMetrics) {
  const auto t = hershey(
      "<text x='10' y='50' font-size='32' text-decoration='underline'>AB"
      "<tspan text-decoration='line-through overline'>C</tspan></text>");
  ASSERT_EQ(t.shapes.size(), 1u);
  const auto& paths = t.shapes[0].paths;
  const std::size_t glyph_paths =
      hershey("<text x='10' y='50' font-size='32'>ABC</text>").shapes[0].paths.size();
  // the glyphs, then one underline under AB and C (C keeps its parent's underline), then
  // C's overline and line-through
  ASSERT_EQ(paths.size(), glyph_paths + 4);
  const double ab = width_of("AB", "futural", 32), abc = width_of("ABC", "futural", 32);
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
  const auto d = import_svg(doc("<text x='10' y='50' font-size='20' font-family='DejaVu Sans' "
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
  const auto t = hershey(
      "<text x='10' y='50' font-size='10'>A<tspan baseline-shift='super' font-size='5'>2"
      "</tspan>B<tspan baseline-shift='sub'>c</tspan><tspan baseline-shift='-3'>d</tspan>"
      "<tspan baseline-shift='50%'>e<tspan baseline-shift='1'>f</tspan></tspan></text>");
  std::vector<Vec2> want = expected("A", "futural", 10, 50, 10);
  double x = 10 + width_of("A", "futural", 10);
  const auto add = [&](const char* s, double y, double size) {
    const auto g = expected(s, "futural", x, y, size);
    want.insert(want.end(), g.begin(), g.end());
    x += width_of(s, "futural", size);
  };
  add("2", 50 - 0.4 * 5, 5);
  add("B", 50, 10);
  add("c", 50 + 0.2 * 10, 10);
  add("d", 53, 10);
  add("e", 45, 10);
  add("f", 44, 10);  // nested shifts add up
  expect_same(
      vertices(hershey(
          "<text x='10' y='50' font-size='10'>A<tspan baseline-shift='super' font-size='5'>2"
          "</tspan>B<tspan baseline-shift='sub'>c</tspan><tspan baseline-shift='-3'>d</tspan>"
          "<tspan baseline-shift='50%'>e<tspan baseline-shift='1'>f</tspan></tspan></text>")),
      want);
  EXPECT_EQ(t.glyphs, 7);
}

TEST(TextLayout, LetterAndWordSpacingWidenTheAdvance) {
  const auto t = hershey(
      "<text x='10' y='50' font-size='10' letter-spacing='2' word-spacing='1em'>A B"
      "<tspan letter-spacing='normal'>CD</tspan></text>");
  std::vector<Vec2> want;
  double x = 10;
  const auto add = [&](const char* s, double extra) {
    const auto g = expected(s, "futural", x, 50, 10);
    want.insert(want.end(), g.begin(), g.end());
    x += width_of(s, "futural", 10) + extra;
  };
  add("A", 2);
  add(" ", 2 + 10);
  add("B", 2);
  add("C", 0);
  add("D", 0);
  expect_same(vertices(t), want);
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
  std::vector<Vec2> want = expected("Text", "futural", 48 * k, 48 * k, 24 * k);
  // line 2: the tspan's size is 150% = 36, its dy="1.5em" of its own size (54) below line 1
  const auto l2 = expected("Big", "futural", 48 * k, (48 + 54) * k, 36 * k);
  want.insert(want.end(), l2.begin(), l2.end());
  // line 3: text-anchor middle at 50% (240), y = 75% (270), size 24
  const double w3 = width_of("mid", "futural", 24 * k);
  const auto l3 = expected("mid", "futural", 240 * k - w3 / 2, 270 * k, 24 * k);
  want.insert(want.end(), l3.begin(), l3.end());
  const auto got = vertices(t);
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < got.size(); ++i) EXPECT_LT((got[i] - want[i]).norm(), 0.2) << i;
}

// Text on a path: each glyph's origin at its distance along the path (startOffset plus the
// advances before it), turned to the path's tangent at the glyph's middle. The circle starts
// at (cx + r, cy) and runs clockwise on the page (towards +y): letters stand outside it.
std::vector<Vec2> expected_on_circle(const std::string& s, const char* font, const Vec2& c,
                                     double r, double size, double s0) {
  hershey_font* f = hershey_font_load(font);
  EXPECT_NE(f, nullptr);
  std::vector<Vec2> out;
  const double k = size / 32.0;
  double along = s0;
  for (unsigned char ch : s) {
    const hershey_glyph* g = hershey_font_glyph(f, ch);
    const double w = g->width * k, mid = (along + w / 2) / r, a = along / r;
    const Vec2 origin = c + r * Vec2(std::cos(a), std::sin(a));
    const Vec2 t(-std::sin(mid), std::cos(mid)), down(-t.y(), t.x());
    for (const hershey_path* p = g->paths; p; p = p->next) {
      if (p->nverts < 2) continue;
      for (int i = 0; i < p->nverts; ++i)
        out.push_back(origin + p->verts[i].x * k * t - p->verts[i].y * k * down);
    }
    along += w;
  }
  hershey_font_free(f);
  return out;
}

const char* kCircle = "<defs><circle id='c' cx='100' cy='50' r='40'/></defs>";
constexpr double kCircleLength = 2 * 3.14159265358979323846 * 40;

TEST(TextPath, GlyphsSitOnTheCircleTurnedToItsTangent) {
  const auto t = hershey(std::string(kCircle) +
                         "<text font-size='8'><textPath href='#c'>STRAND</textPath></text>");
  EXPECT_EQ(t.glyphs, 6);
  EXPECT_EQ(t.off_path, 0);
  expect_same(vertices(t), expected_on_circle("STRAND", "futural", Vec2(100, 50), 40, 8, 0.0));
  // and not the straight line through the first glyph's origin (the test can tell)
  const auto straight = expected("STRAND", "futural", 140, 50, 8);
  EXPECT_GT((vertices(t).back() - straight.back()).norm(), 1.0);
}

TEST(TextPath, StartOffsetAsLengthAndPercentOfThePathLength) {
  const auto at30 = hershey(std::string(kCircle) +
                            "<text font-size='8'><textPath xlink:href='#c' startOffset='30'>Ab"
                            "</textPath></text>");
  expect_same(vertices(at30), expected_on_circle("Ab", "futural", Vec2(100, 50), 40, 8, 30));
  const auto quarter = hershey(std::string(kCircle) +
                               "<text font-size='8'><textPath href='#c' startOffset='25%'>Ab"
                               "</textPath></text>");
  expect_same(vertices(quarter),
              expected_on_circle("Ab", "futural", Vec2(100, 50), 40, 8, kCircleLength / 4));
  // a quarter of the way round a clockwise circle is straight below its centre
  EXPECT_NEAR(vertices(quarter).front().x(), 100.0, 8.0);
  EXPECT_GT(vertices(quarter).front().y(), 85.0);
}

TEST(TextPath, AnchorMiddleCentresTheTextOnTheOffset) {
  const auto t = hershey(std::string(kCircle) +
                         "<text font-size='8' text-anchor='middle'><textPath href='#c' "
                         "startOffset='50%'>Plot</textPath></text>");
  const double w = width_of("Plot", "futural", 8);
  expect_same(vertices(t),
              expected_on_circle("Plot", "futural", Vec2(100, 50), 40, 8, kCircleLength / 2 - w / 2));
}

// A straight path gives the same strokes as the text written along it; tspans inside keep
// their size, dx moves along the path, dy across it.
TEST(TextPath, StraightPathMatchesPlainTextAndTspansKeepTheirStyle) {
  const auto t = hershey(
      "<path id='l' d='M 10 50 H 190' stroke='none' fill='none'/><text font-size='10'>"
      "<textPath href='#l'>A<tspan font-size='20' dy='-3'>B</tspan><tspan dx='4'>c</tspan>"
      "</textPath></text>");
  std::vector<Vec2> want = expected("A", "futural", 10, 50, 10);
  const double xb = 10 + width_of("A", "futural", 10);
  const auto b = expected("B", "futural", xb, 47, 20);
  const auto c = expected("c", "futural", xb + width_of("B", "futural", 20) + 4, 47, 10);
  want.insert(want.end(), b.begin(), b.end());
  want.insert(want.end(), c.begin(), c.end());
  expect_same(vertices(t), want);
}

// SVG 1.1, 10.13.3: a glyph whose middle lies before the start or past the end of the path is
// not drawn; it is counted.
TEST(TextPath, GlyphsPastEitherEndAreDropped) {
  const std::string path = "<path id='l' d='M 10 50 H 40'/>";  // 30 long
  const std::string s = "ABCDEFGH";
  const auto t = hershey(path + "<text font-size='10'><textPath href='#l'>" + s +
                         "</textPath></text>");
  std::size_t fits = 0;
  while (fits < s.size() &&
         width_of(s.substr(0, fits), "futural", 10) + width_of(s.substr(fits, 1), "futural", 10) / 2 <= 30)
    ++fits;
  ASSERT_GT(fits, 2u);
  ASSERT_LT(fits, s.size());
  EXPECT_EQ(t.glyphs, static_cast<int>(fits));
  EXPECT_EQ(t.off_path, static_cast<int>(s.size() - fits));
  expect_same(vertices(t), expected(s.substr(0, fits), "futural", 10, 50, 10));
  EXPECT_NE(t.summary().find(std::to_string(s.size() - fits) + " character(s) off their path"),
            std::string::npos);
  // the first glyph's middle before the start: dropped, the second drawn
  const double wa = width_of("A", "futural", 10);
  const auto early = hershey(path + "<text font-size='10'><textPath href='#l' startOffset='" +
                             std::to_string(-0.6 * wa) + "'>AB</textPath></text>");
  EXPECT_EQ(early.glyphs, 1);
  expect_same(vertices(early), expected("B", "futural", 10 + 0.4 * wa, 50, 10));
}

TEST(TextPath, MissingOrUnusableReferenceSkipsTheTextWithANote) {
  const auto d = import_svg(
      doc("<g id='g'/><text><textPath href='#nope'>abc</textPath></text>"
          "<text id='t2'><textPath href='#g'>abc</textPath></text>"
          "<text><textPath>abc</textPath></text>"
          "<text x='5' y='9'>kept</text><rect width='5' height='5'/>"),
      "t.svg");
  ASSERT_EQ(d.texts.size(), 1u);
  EXPECT_EQ(d.shapes.size(), 1u);
  const std::vector<std::string> want = {
      "<text id=\"t2\"> <textPath href=\"#g\">: not a path or basic shape (text skipped) (1)",
      "<text> <textPath href=\"\">: no href or path (text skipped) (1)",
      "<text> <textPath href=\"#nope\">: no element with that id (text skipped) (1)"};
  EXPECT_EQ(d.skipped, want);
}

// The path's own transform applies (SVG 1.1, 10.13.1); so does the text's.
TEST(TextPath, TransformsOfThePathAndTheTextApply) {
  const auto t = hershey(
      "<defs><circle id='c' r='40' transform='translate(100 50)'/></defs><g "
      "transform='translate(0 10)'><text font-size='8'><textPath href='#c'>Ok</textPath></text>"
      "</g>");
  expect_same(vertices(t), expected_on_circle("Ok", "futural", Vec2(100, 60), 40, 8, 0.0));
}

// An underline on a path bends with the glyphs: a vertex 4 units below each glyph's origin
// (towards the circle's centre here) and one at the run's end, all about 1 mm inside it.
TEST(TextPath, UnderlineFollowsTheCircle) {
  const auto t = hershey(std::string(kCircle) +
                         "<text font-size='8' text-decoration='underline'><textPath "
                         "href='#c'>ABCD</textPath></text>");
  const SubPath& line = t.shapes.at(0).paths.back();
  ASSERT_EQ(line.pieces.size(), 4u);
  EXPECT_NEAR((line.start - Vec2(100, 50)).norm(), 39.0, 0.01);
  for (const auto& piece : line.pieces) EXPECT_NEAR((piece.end() - Vec2(100, 50)).norm(), 39.0, 0.01);
  // it ends where the text does, width / r round the circle
  const double a = width_of("ABCD", "futural", 8) / 40;
  // (the last vertex hangs 1 mm below the last glyph's end, turned to its middle's tangent)
  EXPECT_LT((line.pieces.back().end() - (Vec2(100, 50) + 39 * Vec2(std::cos(a), std::sin(a)))).norm(),
            0.1);
}

TEST(TextPath, OutlineGlyphsFollowThePathToo) {
  const auto d = import_svg(doc(std::string(kCircle) +
                                "<text font-size='10' font-family='DejaVu Sans'><textPath "
                                "href='#c' startOffset='10%'>HIH</textPath></text>"),
                            "t.svg");
  const auto t = layout_text(d.texts, {TextMode::Outline, ""});
  ASSERT_EQ(t.shapes.size(), 1u);
  EXPECT_TRUE(t.shapes[0].filled);
  EXPECT_EQ(t.glyphs, 3);
  // capitals from the baseline on the circle outwards to about 0.73 em
  double lo = INFINITY, hi = 0;
  for (const auto& p : t.shapes[0].paths) {
    EXPECT_TRUE(p.closed);
    for (const auto& q : flatten(p, 0.001)) {
      const double r = (q - Vec2(100, 50)).norm();
      lo = std::min(lo, r), hi = std::max(hi, r);
    }
  }
  EXPECT_NEAR(lo, 40.0, 0.3);  // the baselines are chords: their middles 0.2 mm inside
  EXPECT_NEAR(hi, 47.3, 0.3);
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
        const auto d = import_svg(doc("<text x='150' y='50' font-size='10' font-family='" + family +
                                      "' text-anchor='" + std::string(anchor) + "'>" +
                                      u32_to_utf8(line) + "</text>"),
                                  "t.svg");
        TextOptions o{TextMode::Hershey, "hershey:futural"};
        o.fit_width = fit;
        return vertices(layout_text(d.texts, o)).front().x();
      };
      return x0("start") - x0("end");
    };
    EXPECT_NEAR(width(true), named, 0.01 * named);
    if (family == "DejaVu Sans Mono") {
      EXPECT_GT(std::abs(width(false) - named), 0.05 * named);
    }
  }
  // only across: the letters keep their height
  const auto d = import_svg(doc("<text x='10' y='50' font-size='10' font-family='DejaVu Sans "
                                "Mono'>Hd</text>"),
                            "t.svg");
  TextOptions fit{TextMode::Hershey, ""};
  fit.fit_width = true;
  const auto a = vertices(layout_text(d.texts, fit));
  const auto b = vertices(layout_text(d.texts, {TextMode::Hershey, ""}));
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
  const auto t = hershey("<text x='20' y='50' font-size='12'>Ab</text>");
  const auto back = import_svg(write_svg({{"m2", "label", t.shapes}}, 1.0, 0.3), "back.svg");
  ASSERT_EQ(back.shapes.size(), 1u);
  EXPECT_EQ(back.shapes[0].group_ids, std::vector<std::string>{"m2"});
  EXPECT_EQ(back.shapes[0].layer_labels, std::vector<std::string>{"label"});
  // the page is the text's bounds + 1 mm, so the importer's origin is shifted
  const auto a = vertices(t);
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
