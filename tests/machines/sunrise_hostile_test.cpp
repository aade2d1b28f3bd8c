// Hostile names and profile strings in the Sunrise application stay text (issue 24: code
// injection): output names, CSV folders and profile names with quotes, \u escapes, comment
// ends and Unicode line separators compile to exactly the strings given; identifiers must be
// Java identifiers; line breaks are refused when the profile is read.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "machines/sunrise_writer.h"
#include "tests/machines/sunrise_harness.h"
#include "tests/support/cli_runner.h"

namespace strand::machines {
namespace {

using namespace sunrise_test;

const char* const kScaffold =
    "scaffold --nozzle 0.8 --gap 1.5 --size 20x20 --layers 1 --substrate cylinder "
    "--substrate-radius 25 --substrate-length 60";

TEST(SunriseWriter, HostileOutputNamesAndCsvDirsStayStrings) {
  // Quotes, backslashes, \u escapes (javac replaces them before lexing), comment ends, Java
  // line terminators and other Unicode line separators.
  const std::vector<std::string> dirs = {
      "C:/a\";static{INJ42();}static String q=\"",
      "C:\\u0022;static{INJ42();}//",
      "C:\\\\u0022;INJ42();",
      "C:/x*/INJ42();/*",
      "C:/a\xc2\x85static{INJ42();}",      // NEL
      "C:/a\xe2\x80\xa8static{INJ42();}",  // LINE SEPARATOR
      "C:/\xf0\x9f\x98\x80 \\ end\\",      // outside the BMP; a trailing backslash
  };
  for (const std::string& csv_dir : dirs) {
    const std::string dir = testing::fresh_dir("inject");
    const std::string machine = profile_with(dir, {{"csv_dir", csv_dir}});
    const std::string output = "a\";static{INJ42();}static String q=\"\\u0022.csv";
    const auto r = testing::run_strand(
        std::string(kScaffold) + " --machine " + quoted(machine) + " -o " + quoted(output), dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string cls = java_class_name(output.substr(0, output.size() - 4));
    ASSERT_TRUE(testing::exists(dir + "/" + cls + ".java")) << cls;
    ASSERT_EQ(compile(dir, cls + ".java"), "") << csv_dir;
    const Shell constants = run_java(dir, cls, "constants");
    ASSERT_EQ(constants.exit_code, 0) << constants.out;
    // The strings' values are exactly the names given.
    std::string want_dir, want_name;
    for (const std::string* s : {&csv_dir, &output}) {
      std::string& want = s == &csv_dir ? want_dir : want_name;
      std::u16string u;
      // UTF-8 -> UTF-16 units, shown as Main.shown does.
      for (std::size_t i = 0; i < s->size();) {
        unsigned char c = static_cast<unsigned char>((*s)[i]);
        char32_t cp;
        int n = c < 0x80 ? 1 : c < 0xe0 ? 2 : c < 0xf0 ? 3 : 4;
        cp = n == 1 ? c : c & (0xff >> (n + 1));
        for (int k = 1; k < n; ++k) cp = (cp << 6) | ((*s)[i + k] & 0x3f);
        i += n;
        if (cp >= 0x10000) {
          u += static_cast<char16_t>(0xd800 + ((cp - 0x10000) >> 10));
          u += static_cast<char16_t>(0xdc00 + ((cp - 0x10000) & 0x3ff));
        } else {
          u += static_cast<char16_t>(cp);
        }
      }
      for (char16_t ch : u) {
        if (ch >= 0x20 && ch <= 0x7e && ch != '\\') {
          want += static_cast<char>(ch);
        } else {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(ch));
          want += buf;
        }
      }
    }
    EXPECT_NE(constants.out.find("CSV_DIR=" + want_dir + "\n"), std::string::npos) << constants.out;
    EXPECT_NE(constants.out.find("CSV_NAME=" + want_name + "\n"), std::string::npos)
        << constants.out;
  }
}

TEST(SunriseWriter, HostileProfileNamesStayComments) {
  for (const std::string name : {"cell\\u000a static{INJ42();}", "cell\xe2\x80\xa8static{INJ42();}",
                                 "cell */ static{INJ42();} /*"}) {
    const std::string dir = testing::fresh_dir("inject-name");
    const std::string machine = profile_with(dir, nlohmann::json::object(), name);
    const auto r = testing::run_strand(
        std::string(kScaffold) + " --machine " + quoted(machine) + " -o p.csv", dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(compile(dir, "P.java"), "")
        << "javac would only fail on the injected INJ42(): " << name;
    const std::string krl = testing::slurp(dir + "/p.src");
    EXPECT_EQ(krl.find("\nstatic"), std::string::npos) << "no line starts with the payload";
  }
}

TEST(SunriseWriter, LineBreaksInProfileStringsAreRefusedWhenTheProfileIsRead) {
  for (const std::string value : {"C:/a\nstatic{INJ42();}", "C:/a\rx"}) {
    const std::string dir = testing::fresh_dir("lines");
    const std::string machine = profile_with(dir, {{"csv_dir", value}});
    const auto r = testing::run_strand(
        std::string(kScaffold) + " --machine " + quoted(machine) + " -o p.csv", dir);
    testing::expect_input_error(r, "robot.sunrise.csv_dir");
    EXPECT_FALSE(testing::exists(dir + "/P.java"));
  }
  const std::string dir = testing::fresh_dir("lines-name");
  const std::string machine = profile_with(dir, nlohmann::json::object(), "cell\nstatic{INJ42();}");
  const auto r = testing::run_strand(
      std::string(kScaffold) + " --machine " + quoted(machine) + " -o p.csv", dir);
  testing::expect_input_error(r, "name");
  EXPECT_FALSE(testing::exists(dir + "/P.java"));
}

TEST(SunriseWriter, IdentifiersInTheProfileMustBeJavaIdentifiers) {
  for (const auto& [key, value] :
       std::vector<std::pair<std::string, std::string>>{{"io_group", "Ex;static{INJ42();}"},
                                                        {"lap_signal", "Lap\\u0028"},
                                                        {"lap_signal", "class"},
                                                        {"io_group", "9Group"},
                                                        {"io_group", ""},
                                                        {"ready_signal", "Ready()==x;INJ42();//"},
                                                        {"tool_template", "Cyl\";INJ42();//"},
                                                        {"tool_frame", "Cylinder"},
                                                        {"nozzle_frame", "/Noz\"+INJ42()+\""},
                                                        {"nozzle_frame", "/Cell//Nozzle"},
                                                        {"nozzle_frame", "/"}}) {
    const std::string dir = testing::fresh_dir("ident");
    const std::string machine = profile_with(dir, {{key, value}});
    const auto r = testing::run_strand(
        std::string(kScaffold) + " --machine " + quoted(machine) + " -o p.csv", dir);
    testing::expect_input_error(r, "robot.sunrise." + key);
    EXPECT_FALSE(testing::exists(dir + "/p.csv"));
    EXPECT_FALSE(testing::exists(dir + "/P.java"));
  }
}

TEST(SunriseWriter, ClassNamesAreJavaIdentifiersThatDoNotShadowTheImports) {
  EXPECT_EQ(java_class_name("missing-rib-cylinder"), "MissingRibCylinder");
  EXPECT_EQ(java_class_name("3d part"), "Strand3dPart");
  EXPECT_EQ(java_class_name("tool"), "ToolApplication");
  EXPECT_EQ(java_class_name("frame"), "FrameApplication");
  EXPECT_EQ(java_class_name("\xc3\xa9t\xc3\xa9"), "T");
  EXPECT_EQ(java_class_name("--"), "Strand");
  EXPECT_LE(java_class_name(std::string(500, 'a')).size(), 64u);
}

}  // namespace
}  // namespace strand::machines
