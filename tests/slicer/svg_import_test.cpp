// SVG import against analytic shapes: circles, transformed rects, relative vs absolute
// paths, units, viewBox, use, hidden and skipped elements, and malformed input.
#include "slicer/svg_import.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "slicer/input_error.h"
#include "slicer/svg_syntax.h"

namespace strand::slicer {
namespace {

std::string doc(
    const std::string& body,
    const std::string& root = "width=\"100mm\" height=\"100mm\" viewBox=\"0 0 100 100\"") {
  return "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:xlink=\"http://www.w3.org/1999/xlink\" " +
         root + " fill=\"none\" stroke=\"black\">" + body + "</svg>";
}

Polyline only_polyline(const SvgDrawing& d, double tol = 0.01) {
  EXPECT_EQ(d.shapes.size(), 1u);
  EXPECT_EQ(d.shapes.at(0).paths.size(), 1u);
  return flatten(d.shapes.at(0).paths.at(0), tol);
}

TEST(SvgImport, CircleRadiusWithinTolerance) {
  const auto pl =
      only_polyline(import_svg(doc("<circle cx=\"50\" cy=\"40\" r=\"20\"/>"), "t"), 0.01);
  for (const auto& p : pl) EXPECT_NEAR((p - Vec2(50, 40)).norm(), 20.0, 0.01);
  EXPECT_LT((pl.front() - pl.back()).norm(), 1e-9);
}

TEST(SvgImport, NestedTransformsBakeIntoRectCorners) {
  const auto pl = only_polyline(import_svg(
      doc("<g transform=\"translate(10 20)\"><g transform=\"rotate(90 5 5)\">"
          "<rect x=\"0\" y=\"0\" width=\"10\" height=\"4\" transform=\"scale(2 1)\"/></g></g>"),
      "t"));
  // rect (0,0)-(20,4) after scale; rotate 90 about (5,5): (x,y) -> (10 - y, x); then +(10,20)
  const std::vector<Vec2> want = {{20, 20}, {20, 40}, {16, 40}, {16, 20}, {20, 20}};
  ASSERT_EQ(pl.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i) EXPECT_LT((pl[i] - want[i]).norm(), 1e-9) << i;
}

TEST(SvgImport, SkewAndMatrixMatchTheirDefinitions) {
  const auto a = only_polyline(import_svg(
      doc("<line x1=\"0\" y1=\"10\" x2=\"0\" y2=\"20\" transform=\"skewX(45)\"/>"), "t"));
  EXPECT_LT((a[1] - Vec2(20, 20)).norm(), 1e-9);
  const auto b = only_polyline(import_svg(
      doc("<line x1=\"1\" y1=\"2\" x2=\"3\" y2=\"4\" transform=\"matrix(1 2 3 4 5 6)\"/>"), "t"));
  EXPECT_LT((b[0] - Vec2(1 + 6 + 5, 2 + 8 + 6)).norm(), 1e-9);
}

TEST(SvgImport, RelativeAndAbsolutePathsGiveTheSameGeometry) {
  const std::string abs =
      "M10 10 L20 10 H30 V20 C30 30 40 30 40 20 S50 10 50 20 Q55 30 60 20 T70 20 A5 8 30 0 1 80 25 "
      "Z";
  const std::string rel =
      "m10 10 l10 0 h10 v10 c0 10 10 10 10 0 s10 -10 10 0 q5 10 10 0 t10 0 a5 8 30 0 1 10 5 z";
  const auto a = only_polyline(import_svg(doc("<path d=\"" + abs + "\"/>"), "t"));
  const auto r = only_polyline(import_svg(doc("<path d=\"" + rel + "\"/>"), "t"));
  ASSERT_EQ(a.size(), r.size());
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_LT((a[i] - r[i]).norm(), 1e-9) << i;
}

TEST(SvgImport, ImplicitRepeatsCompactNumbersAndPackedArcFlags) {
  const auto subs = parse_path_data("M0 0 10 0 10-10-.5.5 m5 5 1e1 0a5 5 0 1010 0");
  ASSERT_EQ(subs.size(), 2u);
  EXPECT_EQ(subs[0].pieces.size(), 3u);  // implicit L after M
  EXPECT_LT((subs[0].pieces[2].end() - Vec2(-0.5, 0.5)).norm(), 1e-12);
  ASSERT_EQ(subs[1].pieces.size(), 2u);  // implicit l after m, then the arc
  EXPECT_EQ(subs[1].pieces[1].kind, CurveKind::Arc);
  EXPECT_LT((subs[1].pieces[1].end() - Vec2(14.5, 5.5) - Vec2(10, 0)).norm(), 1e-9);
}

TEST(SvgImport, ArcRadiiTooSmallAreScaledUp) {
  const CurvePiece a = arc_piece(Vec2(0, 0), 1, 1, 0, false, true, Vec2(10, 0));
  EXPECT_LT((a.end() - Vec2(10, 0)).norm(), 1e-9);
  EXPECT_NEAR(std::abs(a.sweep_rad), 3.14159265358979, 1e-9);
}

TEST(SvgImport, UnitsAndViewBoxScaleToMillimetres) {
  const auto in = import_svg(
      doc("<line x1=\"0\" y1=\"0\" x2=\"96\" y2=\"0\"/>", "width=\"2in\" height=\"1in\""), "t");
  EXPECT_NEAR(flatten(in.shapes[0].paths[0], 0.01)[1].x(), 25.4, 1e-9);
  EXPECT_NEAR(in.page_mm.x(), 50.8, 1e-9);
  const auto pt = import_svg(
      doc("<line x1=\"0\" y1=\"0\" x2=\"72pt\" y2=\"0\"/>", "width=\"100\" height=\"100\""), "t");
  EXPECT_NEAR(flatten(pt.shapes[0].paths[0], 0.01)[1].x(), 25.4, 1e-9);
  // meet: a 200x100 viewBox in a 100x100 mm page scales by 0.5 and centres vertically
  const auto vb = import_svg(doc("<line x1=\"0\" y1=\"0\" x2=\"200\" y2=\"0\"/>",
                                 "width=\"100mm\" height=\"100mm\" viewBox=\"0 0 200 100\""),
                             "t");
  const auto pl = flatten(vb.shapes[0].paths[0], 0.01);
  EXPECT_LT((pl[0] - Vec2(0, 25)).norm(), 1e-9);
  EXPECT_LT((pl[1] - Vec2(100, 25)).norm(), 1e-9);
  const auto none = import_svg(
      doc("<line x1=\"0\" y1=\"100\" x2=\"200\" y2=\"100\"/>",
          "width=\"100mm\" height=\"100mm\" viewBox=\"0 0 200 100\" preserveAspectRatio=\"none\""),
      "t");
  EXPECT_LT((flatten(none.shapes[0].paths[0], 0.01)[0] - Vec2(0, 100)).norm(), 1e-9);
}

TEST(SvgImport, UseReferencesHiddenElementsAndTextKept) {
  const auto d = import_svg(
      doc("<defs><rect id=\"r\" width=\"5\" height=\"5\"/></defs>"
          "<use xlink:href=\"#r\" x=\"10\" y=\"20\"/>"
          "<circle r=\"3\" style=\"display: none\"/><g display=\"none\"><line x2=\"5\"/></g>"
          "<line x2=\"5\" visibility=\"hidden\"/><text>hi</text>"),
      "t");
  ASSERT_EQ(d.shapes.size(), 1u);
  EXPECT_LT((flatten(d.shapes[0].paths[0], 0.01)[0] - Vec2(10, 20)).norm(), 1e-9);
  // text is kept as characters for text_layout to draw (tests/slicer/text_layout_test.cpp)
  EXPECT_TRUE(d.skipped.empty());
  ASSERT_EQ(d.texts.size(), 1u);
  EXPECT_EQ(d.texts[0].chars.size(), 2u);
}

TEST(SvgImport, GroupIdsAreCollectedFromEveryAncestor) {
  const auto d =
      import_svg(doc("<g id=\"m3\"><g id=\"inner\"><line x2=\"5\" stroke=\"#F00\"/></g></g>"), "t");
  ASSERT_EQ(d.shapes.size(), 1u);
  EXPECT_EQ(d.shapes[0].group_ids, (std::vector<std::string>{"inner", "m3"}));
  EXPECT_EQ(d.shapes[0].stroke_color, "#ff0000");
}

std::string sample(const std::string& name) {
  std::ifstream in(std::string(STRAND_SOURCE_DIR) + "/samples/plot/" + name);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The exact axis-aligned box of a shape's first sub-path.
std::pair<Vec2, Vec2> box(const SvgShape& s) { return curve_bounds(s.paths.at(0)); }

void expect_box(const SvgShape& s, const Vec2& lo, const Vec2& hi) {
  const auto [a, b] = box(s);
  EXPECT_LT((a - lo).norm(), 1e-6) << a.transpose();
  EXPECT_LT((b - hi).norm(), 1e-6) << b.transpose();
}

TEST(SvgImport, UseSizesSymbolsByTheirViewBoxAndPreserveAspectRatio) {
  const auto d = import_svg(sample("symbols.svg"), "symbols.svg");
  // each tile use: the rect, then the cross (two sub-paths); the wide symbol: its rect
  ASSERT_EQ(d.shapes.size(), 7u);
  expect_box(d.shapes[0], Vec2(5, 5), Vec2(25, 25));    // 10 -> 20: scale 2
  expect_box(d.shapes[2], Vec2(30, 5), Vec2(70, 45));   // 10 -> 40: scale 4
  expect_box(d.shapes[4], Vec2(80, 5), Vec2(110, 20));  // 20x10 meet in 30x30, xMinYMin
  expect_box(d.shapes[5], Vec2(15, 35), Vec2(35, 55));  // 10 meet in 40x20, centred in x
  EXPECT_EQ(d.shapes[3].paths.size(), 2u);
  EXPECT_TRUE(d.skipped.empty());
}

TEST(SvgImport, IllustratorEntitiesDrawTheWholeDrawing) {
  const auto d = import_svg(sample("illustrator_entities.svg"), "illustrator_entities.svg");
  // frame, face, two filled eyes, smile: the switch's foreignObject is not drawn
  ASSERT_EQ(d.shapes.size(), 5u);
  EXPECT_EQ(d.shapes[0].element, "rect");
  EXPECT_EQ(d.shapes[1].element, "circle");
  EXPECT_EQ(d.shapes[2].fill_color, "#e30613");
  EXPECT_FALSE(d.shapes[2].stroked);
  EXPECT_TRUE(d.shapes[1].stroked);
  EXPECT_FALSE(d.shapes[1].filled);  // the style came from &st0;
  EXPECT_EQ(d.shapes[4].group_ids, (std::vector<std::string>{"Smile", "Layer_1"}));
  // 200 px at 96 px/in; eye centres at (70, 75) and (130, 75) px
  const double mm = 25.4 / 96;
  const auto [lo, hi] = box(d.shapes[3]);
  EXPECT_LT(((lo + hi) / 2 - Vec2(130, 75) * mm).norm(), 1e-6);
  EXPECT_NEAR(d.page_mm.x(), 200 * mm, 1e-9);
  EXPECT_TRUE(d.skipped.empty());
}

TEST(SvgImport, SwitchDrawsItsFirstChildWithoutExtensions) {
  const auto d = import_svg(
      doc("<switch><g requiredExtensions=\"http://ns.adobe.com/AdobeIllustrator/10.0/\">"
          "<rect width=\"9\" height=\"9\"/></g><line x2=\"5\"/><circle r=\"3\"/></switch>"),
      "t");
  ASSERT_EQ(d.shapes.size(), 1u);
  EXPECT_EQ(d.shapes[0].element, "line");
}

TEST(SvgImport, IgnoredEffectsAndExternalEntitiesAreCountedAsSkipped) {
  const std::string text =
      "<!DOCTYPE svg [<!ENTITY logo SYSTEM \"logo.xml\"><!ENTITY a \"5\">]>" +
      doc("<line x2=\"&a;\" clip-path=\"url(#c)\"/><line x2=\"5\" mask=\"url(#m)\" "
          "marker-end=\"url(#e)\"/>"
          "<g style=\"clip-path: url(#c)\">&logo;<image href=\"x.png\"/><foreignObject/></g>");
  const auto d = import_svg(text, "t");
  EXPECT_EQ(d.skipped,
            (std::vector<std::string>{"clip-path (2)", "external entity (1)", "foreignObject (1)",
                                      "image (1)", "marker (1)", "mask (1)"}));
  ASSERT_EQ(d.shapes.size(), 2u);
  EXPECT_NEAR(flatten(d.shapes[0].paths[0], 0.01)[1].x(), 5.0, 1e-9);
}

TEST(SvgImport, LimitsAreInputErrorsNamingTheElement) {
  const auto message = [](const std::string& text) {
    try {
      import_svg(text, "t.svg");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  std::string open, close;
  for (int i = 0; i < kMaxSvgDepth; ++i) open += "<g>", close += "</g>";
  EXPECT_EQ(message(doc(open + "<line x2=\"1\"/>" + close)),
            "t.svg: <line>: elements nest deeper than 256 levels");
  EXPECT_EQ(message(doc("<line id=\"a\" x2=\"1e8\"/>")),
            "t.svg: <line id=\"a\">: a coordinate is 1e+08 mm after transforms (at most 1e+07 mm "
            "from the origin)");
  EXPECT_EQ(message(doc("<g id=\"a\"><use href=\"#a\"/></g>")),
            "t.svg: <use href=\"#a\">: references form a cycle");
  // a cycle through a symbol, and a use nesting past the depth through a chain of uses
  EXPECT_EQ(message(doc("<symbol id=\"s\"><use href=\"#s\"/></symbol><use href=\"#s\"/>")),
            "t.svg: <use href=\"#s\">: references form a cycle");
  std::string chain = "<defs><line id=\"u0\" x2=\"1\"/>";
  for (int i = 1; i < 200; ++i) {
    chain +=
        "<g id=\"u" + std::to_string(i) + "\"><use href=\"#u" + std::to_string(i - 1) + "\"/></g>";
  }
  const std::string chained = message(doc(chain + "</defs><use href=\"#u199\"/>"));
  EXPECT_NE(chained.find("nest deeper than 256 levels (each <use> counts as one)"),
            std::string::npos)
      << chained;
}

// The <use> budget counts copies only: a drawing of more plain elements than that (the
// 300,000-line plot benchmark) imports whole, while as many copies made by <use> are refused.
TEST(SvgImport, UseBudgetCountsCopiesNotPlainElements) {
  const std::size_t n = kMaxSvgUseCopies + 10;
  std::string lines;
  lines.reserve(n * 24);
  for (std::size_t i = 0; i < n; ++i) lines += "<line x2=\"" + std::to_string(i % 97 + 1) + "\"/>";
  EXPECT_EQ(import_svg(doc(lines), "t.svg").shapes.size(), n);
  std::string copies = "<defs><g id=\"row\">";
  for (int i = 0; i < 1000; ++i) copies += "<line x2=\"1\"/>";
  copies += "</g></defs>";
  for (std::size_t i = 0; i < kMaxSvgUseCopies / 1000 + 1; ++i) copies += "<use href=\"#row\"/>";
  try {
    import_svg(doc(copies), "t.svg");
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("more than 250000 elements copied by <use>"),
              std::string::npos)
        << e.what();
  }
}

TEST(SvgImport, BadInputThrowsInputError) {
  EXPECT_THROW(import_svg("<svg><g></svg>", "t"), InputError);
  EXPECT_THROW(
      import_svg("<svg xmlns='http://www.w3.org/2000/svg' width='10furlong' height='1'/>", "t"),
      InputError);
  EXPECT_THROW(import_svg(doc("<use href=\"#nope\"/>"), "t"), InputError);
  EXPECT_THROW(import_svg("<html/>", "t"), InputError);
}

// em of the element's own font-size, ex of half of it, % of the viewport's width (x, cx,
// width, rx, x1, x2), height (y, cy, height, ry, y1, y2) or normalised diagonal (r,
// stroke-width), on a 200 x 100 viewport in mm (one user unit = 1 mm).
TEST(SvgImport, RelativeLengthsOnEveryAttributeKind) {
  const std::string root = "width=\"200mm\" height=\"100mm\" viewBox=\"0 0 200 100\"";
  const auto corners = [&](const std::string& body) {
    const auto d = import_svg(doc(body, root), "t");
    EXPECT_EQ(d.skipped, std::vector<std::string>{});
    return flatten(d.shapes.at(0).paths.at(0), 0.01);
  };
  const double diag = std::sqrt((200.0 * 200 + 100.0 * 100) / 2);
  // rect: x 10% of 200, y 1em of 10 = 10, width 2em = 20, height 50% of 100
  auto r = corners("<rect font-size=\"10\" x=\"10%\" y=\"1em\" width=\"2em\" height=\"50%\"/>");
  EXPECT_LT((r[0] - Vec2(20, 10)).norm(), 1e-9);
  EXPECT_LT((r[2] - Vec2(40, 60)).norm(), 1e-9);
  // circle: cx 25% of width, cy 4ex of 10 (ex = 0.5em), r 10% of the diagonal
  auto c = corners("<circle style=\"font-size:10px\" cx=\"25%\" cy=\"4ex\" r=\"10%\"/>");
  for (const auto& p : c) EXPECT_NEAR((p - Vec2(50, 20)).norm(), 0.1 * diag, 0.01);
  // ellipse rx % of width, ry em; line ends in %; font-size inherited from the group
  auto e = corners("<g font-size=\"4\"><ellipse cx=\"100\" cy=\"50\" rx=\"5%\" ry=\"1.5em\"/></g>");
  double max_x = 0, max_y = 0;
  for (const auto& p : e) max_x = std::max(max_x, p.x() - 100), max_y = std::max(max_y, p.y() - 50);
  EXPECT_NEAR(max_x, 10.0, 0.01);
  EXPECT_NEAR(max_y, 6.0, 0.01);
  auto l = corners("<line x1=\"50%\" y1=\"50%\" x2=\"100%\" y2=\"2em\"/>");
  EXPECT_LT((l[0] - Vec2(100, 50)).norm(), 1e-9);
  EXPECT_LT((l[1] - Vec2(200, 32)).norm(), 1e-9);  // the default font-size is 16
  // rx in em on a rect (ry follows rx), stroke-width in % and em, use x/y in %
  const auto d =
      import_svg(doc("<line id=\"a\" x2=\"1\" stroke-width=\"1%\"/>"
                     "<line id=\"b\" x2=\"1\" font-size=\"8\" style=\"stroke-width:0.25em\"/>"
                     "<defs><line id=\"u\" x2=\"1\"/></defs><use href=\"#u\" x=\"10%\" y=\"10%\"/>",
                     root),
                 "t");
  ASSERT_EQ(d.shapes.size(), 3u);
  EXPECT_NEAR(d.shapes[0].stroke_width_mm, 0.01 * diag, 1e-9);
  EXPECT_NEAR(d.shapes[1].stroke_width_mm, 2.0, 1e-9);
  EXPECT_LT((d.shapes[2].paths[0].start - Vec2(20, 10)).norm(), 1e-9);
}

// The W3C regression of issue 19: dy="1em", x="50%" and font-size="inherit" are valid SVG
// and import; an unknown unit skips only its element, with a note naming it.
TEST(SvgImport, UnknownUnitsSkipTheirElementWithANote) {
  const auto d =
      import_svg(doc("<text x=\"50%\" font-size=\"inherit\"><tspan dy=\"1em\">a</tspan></text>"
                     "<rect id=\"bad\" width=\"5furlong\" height=\"1\"/><line x2=\"5\"/>"
                     "<line x2=\"5\" stroke-width=\"2q\"/><text font-size=\"2q\" x=\"1\">b</text>"),
                 "t");
  ASSERT_EQ(d.shapes.size(), 2u);  // both lines; the second keeps the inherited stroke-width
  EXPECT_NEAR(d.shapes[1].stroke_width_mm, 1.0, 1e-9);
  ASSERT_EQ(d.texts.size(), 2u);
  EXPECT_NEAR(*d.texts[0].chars.at(0).x, 50.0, 1e-9);
  EXPECT_NEAR(d.texts[0].chars.at(0).dy, 16.0, 1e-9);
  EXPECT_NEAR(d.texts[1].chars.at(0).style.font_size, 16.0, 1e-9);
  EXPECT_EQ(d.skipped,
            (std::vector<std::string>{
                "<line> stroke-width = \"2q\": not valid (left out) (1)",
                "<rect id=\"bad\"> width = \"5furlong\": not a length (element skipped) (1)",
                "<text> font-size = \"2q\": not valid (left out) (1)"}));
}

}  // namespace
}  // namespace strand::slicer
