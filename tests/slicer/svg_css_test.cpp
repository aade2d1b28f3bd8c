// CSS in SVG: the tokenizer and rule parser (declarations, !important, comments, strings,
// escapes, at-rules counted), selector specificity against hand-computed values, and the
// cascade through import_svg (sheet vs style attribute vs presentation attributes,
// !important, inheritance, Illustrator's class sheets).
#include "slicer/svg_css.h"

#include <gtest/gtest.h>

#include "slicer/input_error.h"
#include "slicer/svg_import.h"

namespace strand::slicer {
namespace {

StyleSheet sheet_of(const std::string& css) {
  StyleSheet s;
  parse_css(css, s);
  return s;
}

TEST(SvgCss, DeclarationsKeepValuesAndImportance) {
  const auto d = parse_css_declarations(
      " FILL : #F00 ; stroke:url(\"a;b\") !important;/* c;d */font-family: 'A B', serif;bad;"
      "stroke-width:1px!IMPORTANT;;");
  ASSERT_EQ(d.size(), 4u);
  EXPECT_EQ(d[0], (CssDeclaration{"fill", "#F00", false}));
  EXPECT_EQ(d[1], (CssDeclaration{"stroke", "url(\"a;b\")", true}));  // ';' inside a string
  EXPECT_EQ(d[2], (CssDeclaration{"font-family", "'A B', serif", false}));
  EXPECT_EQ(d[3], (CssDeclaration{"stroke-width", "1px", true}));
}

TEST(SvgCss, SpecificityCountsIdsClassesAndTypes) {
  // hand-computed (Selectors Level 3, section 9): a = ids, b = classes, c = types
  const auto s = sheet_of(
      "* {fill:red} rect {fill:red} .a {fill:red} #x {fill:red} g > rect.a.b {fill:red}"
      " svg g   rect#x.a {fill:red} *.a {fill:red}");
  ASSERT_EQ(s.rules.size(), 7u);
  const std::vector<std::array<int, 3>> want = {{0, 0, 0}, {0, 0, 1}, {0, 1, 0}, {1, 0, 0},
                                                {0, 2, 2}, {1, 1, 3}, {0, 1, 0}};
  for (std::size_t k = 0; k < want.size(); ++k) {
    EXPECT_EQ(s.rules[k].specificity, want[k]) << k;
    EXPECT_EQ(s.rules[k].order, k);
  }
  ASSERT_EQ(s.rules[4].chain.size(), 2u);
  EXPECT_EQ(s.rules[4].chain[1].combinator, '>');
  EXPECT_EQ(s.rules[4].chain[1].classes, (std::vector<std::string>{"a", "b"}));
  ASSERT_EQ(s.rules[5].chain.size(), 3u);
  EXPECT_EQ(s.rules[5].chain[2].combinator, ' ');
  EXPECT_EQ(s.rules[5].chain[2].id, "x");
}

TEST(SvgCss, GroupsShareTheirDeclarationsAndUnsupportedPartsAreCounted) {
  const auto s = sheet_of(
      "@import url(other.css); @charset \"utf-8\";\n"
      "<!-- .a, .b { stroke : blue } -->\n"
      "a:hover, .c, [fill] {fill:none} .d + .e {fill:none} svg|rect{fill:none}\n"
      "@media print { .a { fill: red } } @font-face { font-family: X } @foo bar;\n"
      ".\\31 x{stroke:red} .f { fill: none");
  // .a, .b, .c, then the escaped class "1x" and the unterminated last rule (closed at the end)
  ASSERT_EQ(s.rules.size(), 5u);
  EXPECT_EQ(s.rules[0].declarations, s.rules[1].declarations);
  EXPECT_EQ(s.rules[3].chain[0].classes, (std::vector<std::string>{"1x"}));
  EXPECT_EQ(s.rules[4].declarations->at(0), (CssDeclaration{"fill", "none", false}));
  EXPECT_EQ(s.skipped, (std::map<std::string, int>{{"CSS @font-face", 1},
                                                   {"CSS @import", 1},
                                                   {"CSS @media", 1},
                                                   {"CSS at-rule", 1},
                                                   {"CSS selector", 4}}));
}

TEST(SvgCss, SheetsRulesAndChainsAreBounded) {
  StyleSheet s;
  parse_css(std::string(kMaxCssBytes, ' '), s);
  parse_css(".a{fill:red}", s);  // past the byte bound: skipped whole
  EXPECT_TRUE(s.rules.empty());
  EXPECT_EQ(s.skipped.at("CSS sheet beyond 1 MiB"), 1);
  std::string chain;
  for (std::size_t k = 0; k <= kMaxCssChain; ++k) chain += "g ";
  const auto deep = sheet_of(chain + "{fill:red}");
  EXPECT_TRUE(deep.rules.empty());
  EXPECT_EQ(deep.skipped.at("CSS selector"), 1);
  std::string many;
  for (std::size_t k = 0; k < kMaxCssRules + 5; ++k) many += ".a,";
  const auto capped = sheet_of(many + ".a{fill:red}");
  EXPECT_EQ(capped.rules.size(), kMaxCssRules);
  EXPECT_EQ(capped.skipped.at("CSS rule beyond 10000"), 6);
}

std::string doc(const std::string& body) {
  return "<svg xmlns='http://www.w3.org/2000/svg' width='100mm' height='100mm' viewBox='0 0 100 "
         "100'>" +
         body + "</svg>";
}

const SvgShape& shape(const SvgDrawing& d, const std::string& id) {
  for (const auto& s : d.shapes) {
    if (s.id == id) return s;
  }
  static const SvgShape none;
  ADD_FAILURE() << "no shape " << id;
  return none;
}

// Colours that the cascade gives each rect, computed by hand from CSS 2.1 section 6.4.
TEST(SvgCss, CascadeOrderMatchesHandComputedStyles) {
  const auto d = import_svg(
      doc("<style>"
          "rect { fill: #000001 } .a { fill: #000002 } #p { fill: #000003 } g rect.a { fill: "
          "#000004 }"
          "g > .b { fill: #000005 } .b { fill: #000006 } .imp { fill: #000007 !important }"
          "#q { stroke: #00000a } rect { stroke: #00000b }"
          "</style>"
          "<g>"
          "<rect id='t' width='1' height='1' fill='#ff0000'/>"  // type rule beats the attribute
          "<rect id='c' class='a' width='1' height='1'/>"       // g rect.a (0,1,2) beats .a
          "<rect id='p' class='a' width='1' height='1'/>"       // id (1,0,0) beats (0,1,2)
          "<rect id='o' class='b' width='1' height='1'/>"       // (0,1,1) g > .b beats .b
          "<rect id='s' class='a' style='fill:#000008' width='1' height='1'/>"     // style beats
                                                                                   // sheets
          "<rect id='i' class='imp' style='fill:#000009' width='1' height='1'/>"   // !important
                                                                                   // beats style
          "<rect id='q' width='1' height='1' style='stroke:#00000c !important'/>"  // style
                                                                                   // !important
                                                                                   // wins
          "</g><rect id='n' class='b' width='1' height='1'/>"),  // not in a g: only .b
      "t.svg");
  EXPECT_EQ(shape(d, "t").fill_color, "#000001");
  EXPECT_EQ(shape(d, "c").fill_color, "#000004");
  EXPECT_EQ(shape(d, "p").fill_color, "#000003");
  EXPECT_EQ(shape(d, "o").fill_color, "#000005");
  EXPECT_EQ(shape(d, "s").fill_color, "#000008");
  EXPECT_EQ(shape(d, "i").fill_color, "#000007");
  EXPECT_EQ(shape(d, "q").stroke_color, "#00000c");
  EXPECT_EQ(shape(d, "t").stroke_color, "#00000b");
  EXPECT_EQ(shape(d, "n").fill_color, "#000006");
}

TEST(SvgCss, SheetsStyleGroupsWhoseChildrenInheritAndInheritKeepsTheParent) {
  const auto d = import_svg(
      doc("<style>.red { stroke: red } .thick { stroke-width: 2 } * > #deep { fill: none }</style>"
          "<g class='red thick' fill='none'>"
          "<line id='l' x2='10'/>"
          "<rect id='r' width='1' height='1' stroke='inherit' stroke-width='inherit'/>"
          "<g stroke='blue'><line id='b' x2='10'/></g>"
          "<rect id='deep' width='1' height='1' fill='black'/>"
          "</g>"),
      "t.svg");
  EXPECT_EQ(shape(d, "l").stroke_color, "#ff0000");
  EXPECT_NEAR(shape(d, "l").stroke_width_mm, 2.0, 1e-12);
  EXPECT_EQ(shape(d, "r").stroke_color, "#ff0000");
  EXPECT_FALSE(shape(d, "r").filled);
  EXPECT_EQ(shape(d, "b").stroke_color, "#0000ff");
  EXPECT_FALSE(shape(d, "deep").filled);
}

// Adobe Illustrator writes every style as a class in one <style> sheet inside CDATA
// (as in vpype's documentation drawings): connector lines are strokes, boxes unfilled,
// the font size of the text comes from the sheet.
TEST(SvgCss, IllustratorClassSheetsPlotAsABrowserShowsThem) {
  const auto d = import_svg(
      "<?xml version='1.0' encoding='utf-8'?>\n"
      "<svg version='1.1' id='Layer_1' xmlns='http://www.w3.org/2000/svg' x='0px' y='0px' "
      "viewBox='0 0 200 100' style='enable-background:new 0 0 200 100;' xml:space='preserve'>\n"
      "<style type='text/css'>\n<![CDATA[\n"
      "\t.st0{fill:#FFFFFF;stroke:#000000;stroke-miterlimit:10;}\n"
      "\t.st1{font-family:'ArialMT';}\n\t.st2{fill:none;stroke:#000000;}\n"
      "\t.st3{font-size:24px;}\n]]>\n</style>\n"
      "<rect id='box' x='10' y='10' class='st2' width='60' height='30'/>\n"
      "<line id='connector' class='st2' x1='70' y1='25' x2='120' y2='25'/>\n"
      "<polyline id='arrow' class='st2' points='115,20 120,25 115,30'/>\n"
      "<rect id='white' x='120' y='10' class='st0' width='60' height='30'/>\n"
      "<text transform='matrix(1 0 0 1 20 80)' class='st1 st3'>Box</text>\n"
      "</svg>",
      "illustrator.svg");
  EXPECT_FALSE(shape(d, "box").filled);
  EXPECT_TRUE(shape(d, "box").stroked);
  EXPECT_TRUE(shape(d, "connector").stroked);
  EXPECT_TRUE(shape(d, "arrow").stroked);
  EXPECT_FALSE(shape(d, "arrow").filled);
  EXPECT_TRUE(shape(d, "white").filled);
  EXPECT_EQ(shape(d, "white").fill_color, "#ffffff");
  ASSERT_EQ(d.texts.size(), 1u);
  EXPECT_DOUBLE_EQ(d.texts[0].chars.at(0).style.font_size, 24.0);
  EXPECT_EQ(d.texts[0].chars.at(0).style.font_family, "'ArialMT'");
}

TEST(SvgCss, XmlStylesheetInsideTheFileAppliesAndExternalOnesAreNeverLoaded) {
  const auto d = import_svg(
      "<?xml-stylesheet type='text/css' href='#sheet'?>\n"
      "<?xml-stylesheet href='https://example.com/evil.css'?>\n"
      "<svg xmlns='http://www.w3.org/2000/svg' width='10' height='10'>"
      "<defs><style id='sheet'>line { stroke: #123456 }</style>"
      "<style type='text/sass'>line { stroke: red }</style></defs>"
      "<line id='l' x2='5'/></svg>",
      "t.svg");
  EXPECT_EQ(shape(d, "l").stroke_color, "#123456");
  EXPECT_EQ(d.skipped, (std::vector<std::string>{"external style sheet (never loaded) (1)",
                                                 "style sheet of type text/sass (1)"}));
}

TEST(SvgCss, UnsupportedRulesAreListedAsSkipped) {
  const auto d = import_svg(
      doc("<style>@import 'x.css'; line:first-child{stroke:red} line{stroke:blue}</style>"
          "<line id='l' x2='5'/>"),
      "t.svg");
  EXPECT_EQ(shape(d, "l").stroke_color, "#0000ff");
  EXPECT_EQ(d.skipped, (std::vector<std::string>{"CSS @import (1)", "CSS selector (1)"}));
}

// Chains of descendant selectors that backtrack over a deep tree are bounded by the match
// steps, never a hang.
TEST(SvgCss, BacktrackingMatchesAreBounded) {
  std::string open, close;
  for (int k = 0; k < 200; ++k) open += "<g>", close += "</g>";
  std::string sel = "rect ";  // never matches: every way to place the g's is tried
  for (int k = 0; k < 20; ++k) sel += "g ";
  std::string leaves;
  for (int k = 0; k < 10; ++k) leaves += "<line x2='1'/>";
  try {
    import_svg(doc("<style>" + sel + "line { stroke: red }</style>" + open + leaves + close),
               "t.svg");
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("CSS selectors need more than 20000000 element tests"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace strand::slicer
