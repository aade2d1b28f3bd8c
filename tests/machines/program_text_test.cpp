// Escapes and checks for text that goes into robot programs (issue 24: code injection).
#include "machines/program_text.h"

#include <gtest/gtest.h>

#include "slicer/input_error.h"

namespace strand::machines {
namespace {

TEST(JavaStringLiteral, KeepsPrintableTextAndEscapesWhatCouldEndIt) {
  EXPECT_EQ(java_string_literal("C:/KRC/ROBOTER/UserFiles", "k"), "\"C:/KRC/ROBOTER/UserFiles\"");
  EXPECT_EQ(java_string_literal("a\"b", "k"), "\"a\\\"b\"");
  EXPECT_EQ(java_string_literal("C:\\dir", "k"), "\"C:\\\\dir\"");
  // A \u escape in the value: its backslash is doubled, so javac sees an escaped backslash
  // followed by "u0022", not a quote.
  EXPECT_EQ(java_string_literal("\\u0022", "k"), "\"\\\\u0022\"");
  EXPECT_EQ(java_string_literal("a\nb\rc", "k"), "\"a\\012b\\015c\"");
  EXPECT_EQ(java_string_literal(std::string("a\0b", 3), "k"), "\"a\\000b\"");
  EXPECT_EQ(java_string_literal("\xc3\xa9", "k"), "\"\\u00e9\"");
  EXPECT_EQ(java_string_literal("\xe2\x80\xa8", "k"), "\"\\u2028\"");
  EXPECT_EQ(java_string_literal("\xf0\x9f\x98\x80", "k"), "\"\\ud83d\\ude00\"");
}

TEST(JavaStringLiteral, RefusesMalformedUtf8NamingTheKey) {
  for (const std::string bad : {"\xff", "\xc3", "\xc0\xaf", "\xed\xa0\x80", "a\xe2\x80"}) {
    try {
      java_string_literal(bad, "robot.sunrise.csv_dir");
      ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("robot.sunrise.csv_dir"), std::string::npos);
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
  }
}

TEST(CommentText, NothingCanEndTheCommentOrFormAUnicodeEscape) {
  EXPECT_EQ(java_comment_text("param gap = 1.5"), "param gap = 1.5");
  EXPECT_EQ(java_comment_text("a\nb\r\xe2\x80\xa8"
                              "c"),
            "a?b????c");
  EXPECT_EQ(java_comment_text("x\\u000a"), "x\\\\u000a");
  EXPECT_EQ(program_comment_text("a\nDEF x()"), "a?DEF x()");
}

TEST(Identifiers, OnlyPlainNamesThatAreNotKeywords) {
  EXPECT_NO_THROW(require_java_identifier("k", "ExtruderIO"));
  EXPECT_NO_THROW(require_java_identifier("k", "_lap2"));
  for (const std::string& bad : std::vector<std::string>{"", "9a", "a b", "a;b", "class", "null",
                                                         "caf\xc3\xa9", std::string(65, 'a')}) {
    EXPECT_THROW(require_java_identifier("robot.sunrise.io_group", bad), InputError) << bad;
  }
  EXPECT_TRUE(is_krl_keyword("end"));
  EXPECT_TRUE(is_krl_keyword("Lin"));
  EXPECT_FALSE(is_krl_keyword("part"));
}

}  // namespace
}  // namespace strand::machines
