// Progress of long commands from the outside: plain phase lines on a pipe (with --progress,
// since the test runs are short), a redrawn bar on a pseudo-terminal, nothing with --quiet,
// and stdout the same byte for byte in every mode.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <pty.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <filesystem>
#include <string>
#include <vector>

#include "tests/support/cli_runner.h"

namespace strand::testing {
namespace {

const std::string kScaffold = "scaffold --nozzle 0.84 --gap 1.6 --size 20x20 --layers 2 -o s.gcode";

struct PtyRun {
  int exit_code = -1;
  std::string terminal;  // what the program wrote to its stderr, a pseudo-terminal
  std::string out;       // its stdout, a file
};

// Runs strand in `dir` with stderr on a pseudo-terminal and stdout in a file.
PtyRun run_on_pty(const std::vector<std::string>& args, const std::string& dir) {
  PtyRun r;
  int master = -1, slave = -1;
  if (::openpty(&master, &slave, nullptr, nullptr, nullptr) != 0) {
    ADD_FAILURE() << "openpty failed";
    return r;
  }
  const std::string out_path = dir + "/.pty-stdout";
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::close(master);
    if (::chdir(dir.c_str()) != 0) ::_exit(127);
    const int out = ::open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(out, STDOUT_FILENO);
    ::dup2(slave, STDERR_FILENO);
    std::vector<char*> argv;
    std::string program = STRAND_CLI;
    argv.push_back(program.data());
    std::vector<std::string> copy = args;
    for (auto& a : copy) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(program.c_str(), argv.data());
    ::_exit(127);
  }
  ::close(slave);
  char buffer[4096];
  while (true) {
    const ssize_t n = ::read(master, buffer, sizeof buffer);
    if (n > 0) {
      r.terminal.append(buffer, static_cast<std::size_t>(n));
    } else if (n < 0 && errno == EINTR) {
      continue;
    } else {
      break;  // EIO once the child has closed its side
    }
  }
  ::close(master);
  int status = 0;
  ::waitpid(pid, &status, 0);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(out_path);
  std::filesystem::remove(out_path);
  return r;
}

TEST(ProgressCli, ShortRunsOnAPipePrintNothingOnStderr) {
  const auto dir = fresh_dir("progress-quiet-default");
  const auto r = run_strand(kScaffold, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
}

TEST(ProgressCli, ProgressFlagPrintsOnePlainLinePerPhase) {
  const auto dir = fresh_dir("progress-lines");
  const auto plain = run_strand(kScaffold, dir);
  const auto r = run_strand(kScaffold + " --progress", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, plain.out) << "progress never touches stdout";
  EXPECT_EQ(r.err.find('\r'), std::string::npos) << "no bar without a terminal";
  // Generation, planning and writing run layer by layer: one phase.
  for (const char* line : {"scaffold: 1/4 generating (", "scaffold: 2/4 planning and writing G-code (",
                           "scaffold: 4/4 writing files (", "scaffold: done in "}) {
    EXPECT_NE(r.err.find(line), std::string::npos) << line << " in:\n" << r.err;
  }
  // One line per phase, not per layer or step.
  EXPECT_LE(std::count(r.err.begin(), r.err.end(), '\n'), 7) << r.err;
  // The global flag may also come before the command.
  const auto before = run_strand("--progress " + kScaffold, dir);
  EXPECT_NE(before.err.find("scaffold: 1/4 generating"), std::string::npos) << before.err;
}

TEST(ProgressCli, EveryLongCommandReportsItsPhases) {
  const auto dir = fresh_dir("progress-commands");
  const std::string src = STRAND_SOURCE_DIR;
  ASSERT_EQ(run_strand(kScaffold, dir).exit_code, 0);
  struct Case {
    std::string args, must_show;
  };
  const Case cases[] = {
      {"check s.gcode", "check: 3/3 checked 2 layers ("},
      {"preview s.gcode -o p.png", "preview: 3/3 drawing ("},
      {"plot '" + src + "/samples/plot/lines.svg' --fit 50x50 -o l.gcode", "plot: "},
      {"trace '" + src + "/samples/plot/photo.png' -o t.svg", "trace: 2/3 tracing ("},
      {"slice '" + src + "/tests/data/box-20x20x3.stl' --nozzle 0.6 --gap 1 "
       "--machine marlin-xyz-200 -o b.gcode",
       "slice: 4/6 filling layers, planning and writing G-code ("},
  };
  for (const auto& c : cases) {
    const auto quiet = run_strand(c.args, dir);
    const auto r = run_strand(c.args + " --progress", dir);
    ASSERT_EQ(r.exit_code, quiet.exit_code) << c.args << ": " << r.err;
    EXPECT_EQ(r.out, quiet.out) << c.args;
    EXPECT_NE(r.err.find(c.must_show), std::string::npos) << c.args << ":\n" << r.err;
    EXPECT_NE(r.err.find("done in "), std::string::npos) << c.args << ":\n" << r.err;
  }
}

TEST(ProgressCli, QuietSilencesEvenTheProgressFlagAndSweeps) {
  const auto dir = fresh_dir("progress-quiet");
  const auto r = run_strand(kScaffold + " --progress --quiet", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  const std::string sweep =
      "sweep '" + std::string(STRAND_SOURCE_DIR) + "/samples/sweeps/scaffold-nozzle-gap.json' -o sw " +
      "--no-previews -j 1";
  const auto loud = run_strand(sweep, dir);
  ASSERT_EQ(loud.exit_code, 0) << loud.err;
  EXPECT_NE(loud.err.find("sweep: 1/"), std::string::npos) << "a sweep prints its points: " << loud.err;
  const auto quiet = run_strand("--quiet " + sweep, fresh_dir("progress-quiet-sweep"));
  ASSERT_EQ(quiet.exit_code, 0) << quiet.err;
  EXPECT_EQ(quiet.err, "");
  EXPECT_EQ(quiet.out, loud.out);
}

TEST(ProgressCli, ABarWithPhaseAndTimeOnATerminalErasedAtTheEnd) {
  const auto dir = fresh_dir("progress-pty");
  const std::vector<std::string> args = {"scaffold", "--nozzle", "0.84", "--gap", "1.6", "--size",
                                         "20x20",    "--layers", "2",    "-o",    "s.gcode"};
  const PtyRun r = run_on_pty(args, dir);
  ASSERT_EQ(r.exit_code, 0) << r.terminal;
  EXPECT_NE(r.terminal.find("\r\033[Kscaffold ["), std::string::npos) << r.terminal;
  EXPECT_NE(r.terminal.find("] 1/4 generating"), std::string::npos) << r.terminal;
  EXPECT_NE(r.terminal.find("] 2/4 planning and writing G-code"), std::string::npos) << r.terminal;
  EXPECT_NE(r.terminal.find(" elapsed"), std::string::npos) << r.terminal;
  EXPECT_TRUE(r.terminal.ends_with("\r\033[K")) << "the bar is erased: " << r.terminal;
  EXPECT_EQ(r.terminal.find('\n'), std::string::npos) << "redrawn in place: " << r.terminal;
  EXPECT_EQ(r.out, run_strand(kScaffold, dir).out);

  std::vector<std::string> quiet = args;
  quiet.push_back("--quiet");
  const PtyRun q = run_on_pty(quiet, dir);
  ASSERT_EQ(q.exit_code, 0);
  EXPECT_EQ(q.terminal, "");
}

TEST(ProgressCli, AnErrorOnATerminalStartsOnAClearedLine) {
  const auto dir = fresh_dir("progress-pty-error");
  const PtyRun r = run_on_pty({"scaffold", "--nozzle", "0.84", "--gap", "1.6", "--size", "300x300",
                               "--layers", "2", "-o", "s.gcode"},
                              dir);
  EXPECT_EQ(r.exit_code, 2);
  const auto at = r.terminal.find("strand: error: ");
  ASSERT_NE(at, std::string::npos) << r.terminal;
  EXPECT_TRUE(at == 0 || r.terminal.substr(0, at).ends_with("\r\033[K")) << r.terminal;
}

}  // namespace
}  // namespace strand::testing
