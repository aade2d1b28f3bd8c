// Text along a <textPath> against the font data itself: glyphs on a circle turned to its
// tangent, startOffset as a length and a percentage, anchors, straight paths, glyphs past
// either end of the path, references, transforms, decorations and outline glyphs.
#include <gtest/gtest.h>

extern "C" {
#include <hersheyfont.h>
}

#include "slicer/text_layout.h"
#include "tests/support/text_strokes.h"

namespace strand::slicer {
namespace {

using testing::expect_same_points;
using testing::hershey_expected;
using testing::hershey_text;
using testing::hershey_width;
using testing::svg_doc;
using testing::text_vertices;

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
  const auto t = hershey_text(std::string(kCircle) +
                              "<text font-size='8'><textPath href='#c'>STRAND</textPath></text>");
  EXPECT_EQ(t.glyphs, 6);
  EXPECT_EQ(t.off_path, 0);
  expect_same_points(text_vertices(t),
                     expected_on_circle("STRAND", "futural", Vec2(100, 50), 40, 8, 0.0));
  // and not the straight line through the first glyph's origin (the test can tell)
  const auto straight = hershey_expected("STRAND", "futural", 140, 50, 8);
  EXPECT_GT((text_vertices(t).back() - straight.back()).norm(), 1.0);
}

TEST(TextPath, StartOffsetAsLengthAndPercentOfThePathLength) {
  const auto at30 = hershey_text(std::string(kCircle) +
                                 "<text font-size='8'><textPath xlink:href='#c' startOffset='30'>Ab"
                                 "</textPath></text>");
  expect_same_points(text_vertices(at30),
                     expected_on_circle("Ab", "futural", Vec2(100, 50), 40, 8, 30));
  const auto quarter = hershey_text(std::string(kCircle) +
                                    "<text font-size='8'><textPath href='#c' startOffset='25%'>Ab"
                                    "</textPath></text>");
  expect_same_points(text_vertices(quarter),
                     expected_on_circle("Ab", "futural", Vec2(100, 50), 40, 8, kCircleLength / 4));
  // a quarter of the way round a clockwise circle is straight below its centre
  EXPECT_NEAR(text_vertices(quarter).front().x(), 100.0, 8.0);
  EXPECT_GT(text_vertices(quarter).front().y(), 85.0);
}

TEST(TextPath, AnchorMiddleCentresTheTextOnTheOffset) {
  const auto t = hershey_text(std::string(kCircle) +
                              "<text font-size='8' text-anchor='middle'><textPath href='#c' "
                              "startOffset='50%'>Plot</textPath></text>");
  const double w = hershey_width("Plot", "futural", 8);
  expect_same_points(text_vertices(t), expected_on_circle("Plot", "futural", Vec2(100, 50), 40, 8,
                                                          kCircleLength / 2 - w / 2));
}

// A straight path gives the same strokes as the text written along it; tspans inside keep
// their size, dx moves along the path, dy across it.
TEST(TextPath, StraightPathMatchesPlainTextAndTspansKeepTheirStyle) {
  const auto t = hershey_text(
      "<path id='l' d='M 10 50 H 190' stroke='none' fill='none'/><text font-size='10'>"
      "<textPath href='#l'>A<tspan font-size='20' dy='-3'>B</tspan><tspan dx='4'>c</tspan>"
      "</textPath></text>");
  std::vector<Vec2> want = hershey_expected("A", "futural", 10, 50, 10);
  const double xb = 10 + hershey_width("A", "futural", 10);
  const auto b = hershey_expected("B", "futural", xb, 47, 20);
  const auto c =
      hershey_expected("c", "futural", xb + hershey_width("B", "futural", 20) + 4, 47, 10);
  want.insert(want.end(), b.begin(), b.end());
  want.insert(want.end(), c.begin(), c.end());
  expect_same_points(text_vertices(t), want);
}

// SVG 1.1, 10.13.3: a glyph whose middle lies before the start or past the end of the path is
// not drawn; it is counted.
TEST(TextPath, GlyphsPastEitherEndAreDropped) {
  const std::string path = "<path id='l' d='M 10 50 H 40'/>";  // 30 long
  const std::string s = "ABCDEFGH";
  const auto t =
      hershey_text(path + "<text font-size='10'><textPath href='#l'>" + s + "</textPath></text>");
  std::size_t fits = 0;
  while (fits < s.size() && hershey_width(s.substr(0, fits), "futural", 10) +
                                    hershey_width(s.substr(fits, 1), "futural", 10) / 2 <=
                                30)
    ++fits;
  ASSERT_GT(fits, 2u);
  ASSERT_LT(fits, s.size());
  EXPECT_EQ(t.glyphs, static_cast<int>(fits));
  EXPECT_EQ(t.off_path, static_cast<int>(s.size() - fits));
  expect_same_points(text_vertices(t), hershey_expected(s.substr(0, fits), "futural", 10, 50, 10));
  EXPECT_NE(t.summary().find(std::to_string(s.size() - fits) + " character(s) off their path"),
            std::string::npos);
  // the first glyph's middle before the start: dropped, the second drawn
  const double wa = hershey_width("A", "futural", 10);
  const auto early = hershey_text(path + "<text font-size='10'><textPath href='#l' startOffset='" +
                                  std::to_string(-0.6 * wa) + "'>AB</textPath></text>");
  EXPECT_EQ(early.glyphs, 1);
  expect_same_points(text_vertices(early), hershey_expected("B", "futural", 10 + 0.4 * wa, 50, 10));
}

TEST(TextPath, MissingOrUnusableReferenceSkipsTheTextWithANote) {
  const auto d = import_svg(svg_doc("<g id='g'/><text><textPath href='#nope'>abc</textPath></text>"
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
  const auto t = hershey_text(
      "<defs><circle id='c' r='40' transform='translate(100 50)'/></defs><g "
      "transform='translate(0 10)'><text font-size='8'><textPath href='#c'>Ok</textPath></text>"
      "</g>");
  expect_same_points(text_vertices(t),
                     expected_on_circle("Ok", "futural", Vec2(100, 60), 40, 8, 0.0));
}

// An underline on a path bends with the glyphs: a vertex 4 units below each glyph's origin
// (towards the circle's centre here) and one at the run's end, all about 1 mm inside it.
TEST(TextPath, UnderlineFollowsTheCircle) {
  const auto t = hershey_text(std::string(kCircle) +
                              "<text font-size='8' text-decoration='underline'><textPath "
                              "href='#c'>ABCD</textPath></text>");
  const SubPath& line = t.shapes.at(0).paths.back();
  ASSERT_EQ(line.pieces.size(), 4u);
  EXPECT_NEAR((line.start - Vec2(100, 50)).norm(), 39.0, 0.01);
  for (const auto& piece : line.pieces)
    EXPECT_NEAR((piece.end() - Vec2(100, 50)).norm(), 39.0, 0.01);
  // it ends where the text does, width / r round the circle
  const double a = hershey_width("ABCD", "futural", 8) / 40;
  // (the last vertex hangs 1 mm below the last glyph's end, turned to its middle's tangent)
  EXPECT_LT(
      (line.pieces.back().end() - (Vec2(100, 50) + 39 * Vec2(std::cos(a), std::sin(a)))).norm(),
      0.1);
}

TEST(TextPath, OutlineGlyphsFollowThePathToo) {
  const auto d = import_svg(
      svg_doc(std::string(kCircle) + "<text font-size='10' font-family='DejaVu Sans'><textPath "
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

}  // namespace
}  // namespace strand::slicer
