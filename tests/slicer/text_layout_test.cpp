// Text layout against the font data itself: a string's strokes are the Hershey glyphs
// (read straight from libhersheyfont) scaled and placed at the anchor within 0.01 mm;
// tspan offsets, chunks and transforms; white space; outline fonts; missing fonts.
#include "slicer/text_layout.h"

#include <gtest/gtest.h>

extern "C" {
#include <hersheyfont.h>
}

#include "slicer/hershey_font.h"
#include "slicer/input_error.h"
#include "slicer/svg_export.h"

namespace strand::slicer {
namespace {

std::string doc(const std::string& body) {
  return "<svg xmlns='http://www.w3.org/2000/svg' width='200mm' height='100mm' viewBox='0 0 200 100'>" + body + "</svg>";
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
std::vector<Vec2> expected(const std::string& s, const char* font, double x0, double y0, double size) {
  hershey_font* f = hershey_font_load(font);
  EXPECT_NE(f, nullptr);
  std::vector<Vec2> out;
  const double k = size / 32.0;
  double x = x0;
  for (unsigned char ch : s) {
    const hershey_glyph* g = hershey_font_glyph(f, ch);
    for (const hershey_path* p = g->paths; p; p = p->next) {
      if (p->nverts < 2) continue;
      for (int i = 0; i < p->nverts; ++i) out.emplace_back(x + p->verts[i].x * k, y0 - p->verts[i].y * k);
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
  for (const auto& [anchor, factor] : std::vector<std::pair<std::string, double>>{{"middle", 0.5}, {"end", 1.0}}) {
    const auto t = hershey("<text x='100' y='40' font-size='10' text-anchor='" + anchor + "' >AbC</text>", "hershey:rowmans");
    expect_same(vertices(t), expected("AbC", "rowmans", 100 - factor * width_of("AbC", "rowmans", 10), 40, 10));
  }
}

TEST(TextLayout, TspanOffsetsAndAbsolutePositions) {
  // "ab" at (10, 20); tspan "c" shifted by dx=5 dy=-3; tspan "d" starts a new chunk at x=60
  const auto t = hershey("<text x='10' y='20' font-size='8'>ab<tspan dx='5' dy='-3'>c</tspan>"
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
  const auto t = hershey("<g style='font-size:10px'><text x='10 30' y='50'>AB<tspan font-size='150%'>C</tspan></text></g>");
  std::vector<Vec2> want = expected("A", "futural", 10, 50, 10);
  const auto b = expected("B", "futural", 30, 50, 10);
  const auto c = expected("C", "futural", 30 + width_of("B", "futural", 10), 50, 15);
  want.insert(want.end(), b.begin(), b.end());
  want.insert(want.end(), c.begin(), c.end());
  expect_same(vertices(t), want);
}

TEST(TextLayout, TransformsApplyToTheGlyphs) {
  // rotate(90) about the origin then translate: (x, y) -> (100 - y, x)
  const auto t = hershey("<g transform='translate(100 0)'><text transform='rotate(90)' x='10' y='5' font-size='10'>L</text></g>");
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
  const auto d = import_svg(doc("<text x='10' y='50' font-size='20' font-family='DejaVu Sans'>Ob</text>"), "t.svg");
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
  const auto d = import_svg(doc("<text x='0' y='10' font-family='No Such Font Family'>a</text>"), "t.svg");
  try {
    layout_text(d.texts, {TextMode::Outline, ""});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("No Such Font Family"), std::string::npos);
  }
  // a list falls back to the next installed family, as CSS does
  const auto l = import_svg(doc("<text x='0' y='10' font-family=\"'No Such', DejaVu Serif\">a</text>"), "t.svg");
  EXPECT_EQ(layout_text(l.texts, {TextMode::Outline, ""}).fonts.at(0).rfind("DejaVu Serif", 0), 0u);
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
