// Internal-subset DTD entities: expanded in content and attribute values as XML says,
// untouched where XML does not expand them, and refused when they nest, loop or explode.
#include "slicer/svg_entities.h"

#include <gtest/gtest.h>

#include "slicer/input_error.h"

namespace strand::slicer {
namespace {

std::string with_subset(const std::string& subset, const std::string& body) {
  return "<?xml version=\"1.0\"?>\n<!DOCTYPE svg PUBLIC \"-//W3C//DTD SVG 1.1//EN\" "
         "\"http://www.w3.org/Graphics/SVG/1.1/DTD/svg11.dtd\" [\n" +
         subset + "\n]>\n" + body;
}

std::string expanded_body(const std::string& subset, const std::string& body) {
  const auto e = expand_entities(with_subset(subset, body), "t.svg");
  EXPECT_TRUE(e.has_value());
  if (!e) return "";
  const auto at = e->text.find("]>\n");
  return e->text.substr(at + 3);
}

TEST(SvgEntities, DocumentsWithoutInternalEntitiesAreNotCopied) {
  EXPECT_FALSE(expand_entities("<svg xmlns=\"http://www.w3.org/2000/svg\"/>", "t"));
  EXPECT_FALSE(
      expand_entities("<!DOCTYPE svg PUBLIC \"-//W3C//DTD SVG 1.1//EN\" \"x.dtd\"><svg/>", "t"));
  EXPECT_FALSE(expand_entities(with_subset("<!-- only a comment -->", "<svg/>"), "t"));
  // a DOCTYPE after the root element is no prolog
  EXPECT_FALSE(expand_entities("<svg/><!DOCTYPE svg [<!ENTITY a \"b\">]>", "t"));
}

TEST(SvgEntities, IllustratorNamespacesExpandInAttributes) {
  const std::string subset =
      "\t<!ENTITY ns_svg \"http://www.w3.org/2000/svg\">\n\t<!ENTITY ns_xlink "
      "\"http://www.w3.org/1999/xlink\">";
  EXPECT_EQ(
      expanded_body(subset, "<svg xmlns=\"&ns_svg;\" xmlns:xlink='&ns_xlink;'/>"),
      "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:xlink='http://www.w3.org/1999/xlink'/>");
}

TEST(SvgEntities, MarkupInContentNestedReferencesAndFirstDeclarationWins) {
  const std::string subset =
      "<!ENTITY eye \"<circle r='1.5'/>\">\n<!ENTITY face '<g>&eye;&eye;</g>'>\n<!ENTITY eye "
      "\"ignored\">";
  EXPECT_EQ(expanded_body(subset, "<svg>&face;</svg>"),
            "<svg><g><circle r='1.5'/><circle r='1.5'/></g></svg>");
}

TEST(SvgEntities, QuotesAndAnglesAreEscapedInsideAttributeValues) {
  EXPECT_EQ(expanded_body("<!ENTITY q 'say \"hi\" <now>'>", "<svg a=\"&q;\" b='&q;'>&q;</svg>"),
            "<svg a=\"say &quot;hi&quot; &lt;now>\" b='say &quot;hi&quot; &lt;now>'>say \"hi\" "
            "<now></svg>");
}

TEST(SvgEntities, CommentsCdataPredefinedAndUnknownReferencesStayAsWritten) {
  const std::string body =
      "<svg><!-- &a; --><![CDATA[&a;]]><?pi &a;?><text>&amp;&#65;&nope;&a;</text></svg>";
  EXPECT_EQ(expanded_body("<!ENTITY a \"A\">", body),
            "<svg><!-- &a; --><![CDATA[&a;]]><?pi &a;?><text>&amp;&#65;&nope;A</text></svg>");
}

TEST(SvgEntities, ExternalAndParameterEntitiesAreNeverLoaded) {
  const auto e = expand_entities(with_subset("<!ENTITY % pe \"x\">\n%pe;\n<!ENTITY secret SYSTEM "
                                             "\"file:///etc/passwd\">\n<!ENTITY a \"A\">",
                                             "<svg><text>&secret;&a;</text></svg>"),
                                 "t");
  ASSERT_TRUE(e);
  EXPECT_EQ(e->external, 1);
  EXPECT_EQ(e->references, 2);
  EXPECT_NE(e->text.find("<text>A</text>"), std::string::npos);
}

TEST(SvgEntities, BillionLaughsStopsAtTheExpansionLimit) {
  std::string subset = "<!ENTITY l0 \"lol\">\n";
  for (int i = 1; i <= 9; ++i) {
    subset += "<!ENTITY l" + std::to_string(i) + " \"";
    for (int k = 0; k < 10; ++k) subset += "&l" + std::to_string(i - 1) + ";";
    subset += "\">\n";
  }
  try {
    expand_entities(with_subset(subset, "<svg><text>&l9;</text></svg>"), "laughs.svg");
    FAIL() << "a 3 GB expansion was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(
        std::string(e.what()).find("laughs.svg: DTD entities expand to more than 16 MiB (at &l9;)"),
        std::string::npos)
        << e.what();
  }
}

TEST(SvgEntities, EmptyExpansionsStillCountTowardsTheLimit) {
  // 32^5 = 33.5 million references that expand to nothing: work, not output, is bounded
  std::string subset = "<!ENTITY e0 \"\">\n";
  for (int i = 1; i <= 5; ++i) {
    subset += "<!ENTITY e" + std::to_string(i) + " \"";
    for (int k = 0; k < 32; ++k) subset += "&e" + std::to_string(i - 1) + ";";
    subset += "\">\n";
  }
  EXPECT_THROW(expand_entities(with_subset(subset, "<svg>&e5;</svg>"), "t"), InputError);
}

TEST(SvgEntities, CyclesAndDeepNestingAreRefused) {
  try {
    expand_entities(with_subset("<!ENTITY a \"&b;\">\n<!ENTITY b \"x&a;\">", "<svg>&a;</svg>"),
                    "t");
    FAIL() << "a cycle was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("DTD entity &a; refers to itself"), std::string::npos)
        << e.what();
  }
  std::string subset = "<!ENTITY d0 \"x\">\n";
  for (int i = 1; i <= kMaxEntityDepth; ++i) {
    subset += "<!ENTITY d" + std::to_string(i) + " \"&d" + std::to_string(i - 1) + ";\">\n";
  }
  const std::string deepest = "&d" + std::to_string(kMaxEntityDepth) + ";";
  EXPECT_THROW(expand_entities(with_subset(subset, "<svg>" + deepest + "</svg>"), "t"), InputError);
  const std::string ok = "&d" + std::to_string(kMaxEntityDepth - 1) + ";";
  EXPECT_EQ(expanded_body(subset, "<svg>" + ok + "</svg>"), "<svg>x</svg>");
}

TEST(SvgEntities, ARepeatedEntityKeepsItsDepthWhereverItIsReferencedAgain) {
  // d8 spans 9 levels: fine at the top, 18 levels deep when reached again through w0..w8
  std::string subset = "<!ENTITY d0 \"x\">\n<!ENTITY w0 \"&d8;\">\n";
  for (int i = 1; i <= 8; ++i) {
    const std::string n = std::to_string(i), p = std::to_string(i - 1);
    subset += "<!ENTITY d" + n + " \"&d" + p + ";\">\n<!ENTITY w" + n + " \"&w" + p + ";\">\n";
  }
  EXPECT_EQ(expanded_body(subset, "<svg>&d8;&d8;&w0;</svg>"), "<svg>xxx</svg>");
  EXPECT_THROW(expand_entities(with_subset(subset, "<svg>&d8;&w8;</svg>"), "t"), InputError);
}

}  // namespace
}  // namespace strand::slicer
