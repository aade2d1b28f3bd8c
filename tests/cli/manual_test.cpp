// Manual pages and completion from the CLI tables, and `make install` into a prefix.
#include "cli/manual.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "tests/support/cli_runner.h"

namespace strand::testing {
namespace {

TEST(Manual, EveryFlagOfACommandIsOnItsPage) {
  const auto help = run_strand("scaffold --help");
  const auto page = run_strand("manual scaffold");
  ASSERT_EQ(page.exit_code, 0) << page.err;
  EXPECT_EQ(page.out.rfind(".TH STRAND\\-SCAFFOLD 1", 0), 0u) << page.out.substr(0, 80);
  for (const char* flag : {"nozzle", "gap", "size", "machine", "output"}) {
    EXPECT_NE(help.out.find(std::string("--") + flag), std::string::npos) << flag;
    EXPECT_NE(page.out.find(std::string("\\-\\-") + flag), std::string::npos)
        << flag << " missing from the page";
  }
  const auto unknown = run_strand("manual scafold");
  expect_input_error(unknown, "manual: no command 'scafold'");
}

TEST(Manual, RoffEscapesTextThatWouldBeARequest) {
  CLI::App app{"top"};
  auto* sub = app.add_subcommand("demo", ".so /etc/passwd\n'br and a \\ backslash");
  std::string value;
  sub->add_option("--x", value, "-1 is \\fBbold?\\fR\n.ex");
  const auto page = cli::man_page(app, sub, "strand 0");
  EXPECT_EQ(page.find("\n.so"), std::string::npos) << page;
  EXPECT_EQ(page.find("\n'br"), std::string::npos) << page;
  EXPECT_EQ(page.find("\n.ex"), std::string::npos) << page;
  EXPECT_NE(page.find("\\&.so /etc/passwd"), std::string::npos) << page;
  EXPECT_NE(page.find("\\efBbold?\\efR"), std::string::npos) << page;
}

TEST(Manual, PagesFormatWithoutGroffWarnings) {
  const auto dir = fresh_dir("man");
  ASSERT_EQ(run_strand("manual --dir man1", dir).exit_code, 0);
  for (const char* page : {"strand.1", "strand-scaffold.1", "strand-plot.1", "strand-send.1"}) {
    const auto r = run_in_shell(std::string("groff -man -Tutf8 -ww -z man1/") + page, dir);
    EXPECT_EQ(r.exit_code, 0) << page << ": " << r.err;
    EXPECT_EQ(r.err, "") << page;
  }
  const auto text = run_in_shell("groff -man -Tutf8 man1/strand.1 | col -b", dir);
  EXPECT_NE(text.out.find("EXIT STATUS"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("strand-scaffold(1)"), std::string::npos) << text.out;
}

// Completion candidates bash offers after typing `words` (the last one being completed).
std::string complete(const std::string& script, const std::string& words, const std::string& dir) {
  const auto r = run_in_shell("bash -c 'source " + script + "; COMP_WORDS=(" + words +
                                  "); COMP_CWORD=$((${#COMP_WORDS[@]} - 1)); _strand; "
                                  "echo \"${COMPREPLY[*]}\"'",
                              dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return r.out;
}

TEST(Completion, BashCompletesCommandsFlagsAndMachineNames) {
  const auto dir = fresh_dir("completion");
  const auto bash = run_strand("completion bash", dir);
  ASSERT_EQ(bash.exit_code, 0);
  { std::ofstream(dir + "/strand.bash") << bash.out; }
  EXPECT_EQ(complete("strand.bash", "strand scaf", dir), "scaffold\n");
  EXPECT_EQ(complete("strand.bash", "strand scaffold --noz", dir), "--nozzle\n");
  EXPECT_EQ(complete("strand.bash", "strand scaffold --machine deltaw", dir),
            "deltawasp-2040-clay deltawasp-2040-clay-ldm deltawasp-2040-clay-valve\n");
  const auto tetra = complete("strand.bash", "strand tetra", dir);
  EXPECT_EQ(tetra, "tetrachiral\n");
  const auto zsh = run_strand("completion zsh", dir);
  EXPECT_EQ(zsh.out.rfind("#compdef strand\n", 0), 0u);
  EXPECT_NE(zsh.out.find(bash.out), std::string::npos);
  expect_input_error(run_strand("completion fish", dir), "shell");
}

// `make install` is `cmake --install`: the installed program runs a job from any directory
// with nothing of the build tree, and its pages and completion are where man and bash look.
TEST(Install, TheInstalledProgramRunsWithItsProfilesPagesAndCompletion) {
  const auto dir = fresh_dir("install");
  const auto install =
      run_in_shell("cmake --install '" + std::string(STRAND_BUILD_DIR) + "' --prefix prefix", dir);
  ASSERT_EQ(install.exit_code, 0) << install.err;
  for (const char* file :
       {"bin/strand", "share/man/man1/strand.1", "share/man/man1/strand-slice.1",
        "share/bash-completion/completions/strand", "share/zsh/site-functions/_strand",
        "share/strand/machines/deltawasp-2040-clay.json", "share/doc/strand/README.md"}) {
    EXPECT_TRUE(exists(dir + "/prefix/" + file)) << file;
  }
  const auto version = run_in_shell("prefix/bin/strand --version", dir);
  EXPECT_EQ(version.exit_code, 0);
  EXPECT_EQ(version.out, run_strand("--version").out);
  const auto job = run_in_shell(
      "mkdir -p elsewhere && cd elsewhere && ../prefix/bin/strand scaffold --nozzle 0.84 --gap 1.6 "
      "--size 20x20 --height 2 --machine ../prefix/share/strand/machines/deltawasp-2040-clay.json "
      "-o s.gcode",
      dir);
  EXPECT_EQ(job.exit_code, 0) << job.err;
  EXPECT_TRUE(exists(dir + "/elsewhere/s.gcode"));
  EXPECT_EQ(complete("prefix/share/bash-completion/completions/strand", "strand sli", dir),
            "slice\n");
#ifndef STRAND_SANITIZE_BUILD  // debug line tables name the build directory
  const auto paths = run_in_shell(
      "grep -c -F '" + std::string(STRAND_BUILD_DIR) + "' prefix/bin/strand || true", dir);
  EXPECT_EQ(paths.out, "0\n") << "the installed binary names the build tree";
#endif
}

}  // namespace
}  // namespace strand::testing
