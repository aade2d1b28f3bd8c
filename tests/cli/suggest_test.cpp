// "Did you mean" for commands and flags, and --version.
#include "cli/suggest.h"

#include <gtest/gtest.h>

#include "cli/version.h"
#include "tests/support/cli_runner.h"

namespace strand::testing {
namespace {

TEST(EditDistance, CountsInsertionsDeletionsSubstitutionsAndSwaps) {
  EXPECT_EQ(cli::edit_distance("nozle", "nozzle"), 1);
  EXPECT_EQ(cli::edit_distance("sacffold", "scaffold"), 1);  // a swap
  EXPECT_EQ(cli::edit_distance("gap", "gap"), 0);
  EXPECT_EQ(cli::edit_distance("", "abc"), 3);
  EXPECT_EQ(cli::edit_distance("kitten", "sitting"), 3);
  EXPECT_EQ(cli::edit_distance("GAP", "gap"), 0);  // flags are typed in any case
}

TEST(NearestNames, TyposReachTheirNameAndUnrelatedWordsReachNone) {
  const std::vector<std::string> names = {"--nozzle", "--gap", "--size", "--layers"};
  EXPECT_EQ(cli::nearest_names("--nozle", names), std::vector<std::string>{"--nozzle"});
  EXPECT_EQ(cli::nearest_names("--layer", names), std::vector<std::string>{"--layers"});
  EXPECT_TRUE(cli::nearest_names("--temperature", names).empty());
  EXPECT_TRUE(cli::nearest_names(std::string(5000, 'x'), names).empty());
}

TEST(SuggestCli, UnknownCommandNamesTheNearestOne) {
  const auto r = run_strand("scafold --nozzle 0.84");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "strand: error: unknown command 'scafold' (did you mean 'scaffold'?)\n");
  const auto far = run_strand("frobnicate");
  EXPECT_EQ(far.exit_code, 2);
  EXPECT_NE(far.err.find("unknown command 'frobnicate' (commands: "), std::string::npos) << far.err;
  EXPECT_NE(far.err.find("scaffold"), std::string::npos);
}

TEST(SuggestCli, UnknownFlagNamesTheNearestFlagOfItsCommand) {
  const auto dir = fresh_dir("suggest");
  const auto r = run_strand("scaffold --nozle 0.84 --gap 1.6 -o x.gcode", dir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "strand: error: scaffold: unknown flag --nozle (did you mean --nozzle?)\n");
  EXPECT_FALSE(exists(dir + "/x.gcode"));
  const auto eq = run_strand("plot in.svg --machin=xy-plotter-servo", dir);
  EXPECT_EQ(eq.exit_code, 2);
  EXPECT_NE(eq.err.find("plot: unknown flag --machin (did you mean --machine?)"), std::string::npos)
      << eq.err;
}

TEST(SuggestCli, KnownWordsKeepTheParsersOwnMessage) {
  // Every word is known; the refusal is about a value, so no suggestion is made up.
  const auto r = run_strand("scaffold --nozzle");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err.find("unknown"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--nozzle"), std::string::npos) << r.err;
}

TEST(VersionCli, PrintsTheVersionAndTheLibrariesBuiltWith) {
  const auto r = run_strand("--version");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.out, cli::version_text());
  EXPECT_EQ(r.out.rfind("strand 0.", 0), 0u) << r.out;
  EXPECT_NE(r.out.find("\nbuilt with CGAL "), std::string::npos) << r.out;
  for (const char* library : {"OpenMesh ", "Clipper ", "potrace ", "cairo "}) {
    EXPECT_NE(r.out.find(library), std::string::npos) << library;
  }
}

}  // namespace
}  // namespace strand::testing
