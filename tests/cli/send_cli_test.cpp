// `strand send` against a simulated firmware on a pseudo-terminal: under every fault the
// controller executes exactly the file's commands in order, nothing skipped and nothing
// sent twice unless it asked for a resend; errors and lost ports stop with a line to resume
// from, and resuming finishes the job; bad ports and files exit 2 with one line.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <functional>
#include <sstream>
#include <thread>

#include "machines/send/streamer.h"
#include "slicer/file_io.h"
#include "tests/support/cli_runner.h"
#include "tests/support/firmware_sim.h"

namespace strand::testing {
namespace {

const std::string kSamples = std::string(STRAND_SOURCE_DIR) + "/samples/plot/";

// A real plot file (comments, pen commands, dwells) and the commands it holds.
struct Job {
  std::string dir, file;
  std::vector<machines::Command> commands;
};

Job plot_job(const std::string& machine) {
  Job j;
  j.dir = fresh_dir("send");
  j.file = j.dir + "/job.gcode";
  const auto r = run_strand(
      "plot '" + kSamples + "layers.svg' --machine " + machine + " --fit 100x60 -o job.gcode",
      j.dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  j.commands = machines::commands_of(slurp(j.file), j.file);
  return j;
}

std::vector<std::string> texts(const std::vector<machines::Command>& c, std::size_t from = 0) {
  std::vector<std::string> out;
  for (std::size_t i = from; i < c.size(); ++i) out.push_back(c[i].text);
  return out;
}

CliResult send(const Job& j, const FirmwareSim& sim, const std::string& extra = "") {
  return run_strand("send job.gcode --port " + sim.port() + " --timeout 0.3 " + extra, j.dir);
}

struct FaultCase {
  const char* name;
  bool grbl;
  SimFaults faults;
};

class SendUnderFaults : public ::testing::TestWithParam<FaultCase> {};

TEST_P(SendUnderFaults, FirmwareExecutesExactlyTheFileInOrder) {
  const auto& c = GetParam();
  const Job j = plot_job(c.grbl ? "xy-plotter-grbl" : "xy-plotter-servo");
  ASSERT_GT(j.commands.size(), 30u);
  FirmwareSim sim(c.grbl, c.faults);
  const auto r = send(j, sim, c.grbl ? "--firmware grbl" : "");
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_EQ(sim.executed(), texts(j.commands));
  EXPECT_EQ(sim.unrequested_duplicates(), 0);
  if (c.faults.corrupt_at) {
    EXPECT_GE(sim.resend_requests(), 1);
  }
  if (c.grbl) {
    EXPECT_LE(sim.max_buffered(), machines::kGrblBufferBytes);
    EXPECT_GT(sim.max_buffered(), 60u);  // more than one line in flight: character counting
  }
}

INSTANTIATE_TEST_SUITE_P(
    Faults, SendUnderFaults,
    ::testing::Values(FaultCase{"marlin_clean", false, {}},
                      FaultCase{"marlin_dropped_ok", false, {.drop_ok_at = 5}},
                      FaultCase{"marlin_bad_checksum", false, {.corrupt_at = 7}},
                      FaultCase{"marlin_busy_keepalive", false, {.busy_at = 3}},
                      FaultCase{"grbl_clean", true, {}},
                      FaultCase{"grbl_dropped_ok", true, {.drop_ok_at = 5}}),
    [](const auto& info) { return std::string(info.param.name); });

// A firmware error stops the job with its line and message (exit 1); resuming from that
// line on a fresh controller runs the preamble, then exactly the rest of the file.
TEST(SendCli, FirmwareErrorStopsAndTheJobResumes) {
  const Job j = plot_job("xy-plotter-servo");
  int line = 0;
  {
    FirmwareSim sim(false, {.error_at = 12});
    const auto r = send(j, sim, "--machine xy-plotter-servo");
    EXPECT_EQ(r.exit_code, 1);
    line = j.commands[11].file_line;
    EXPECT_NE(
        r.err.find("firmware error at line " + std::to_string(line) + ": Error:Printer halted"),
        std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("--resume-from " + std::to_string(line)), std::string::npos);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1);
    const auto all = texts(j.commands);
    EXPECT_EQ(sim.executed(), std::vector<std::string>(all.begin(), all.begin() + 11));
  }
  FirmwareSim sim(false, {});
  const auto r = send(j, sim, "--machine xy-plotter-servo --resume-from " + std::to_string(line));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto done = sim.executed();
  const auto rest = texts(j.commands, 11);
  ASSERT_GE(done.size(), rest.size());
  // the preamble: units, absolute positions, pen up, then the position before the line
  const std::vector<std::string> preamble(done.begin(),
                                          done.end() - static_cast<long>(rest.size()));
  ASSERT_GE(preamble.size(), 3u);
  EXPECT_EQ(preamble[0], "G21");
  EXPECT_EQ(preamble[1], "G90");
  EXPECT_EQ(preamble[2], "M280 P0 S90");
  EXPECT_EQ(std::vector<std::string>(done.end() - static_cast<long>(rest.size()), done.end()),
            rest);
}

// Starts `strand send ARGS` in the background (stdout to out.txt); returns once it ended.
// signal_when() is polled every 10 ms (at most 20 s); when it says so, `sig` goes to the
// process group as a terminal's Ctrl-C (or a kill, or a hangup) reaches the foreground job.
CliResult send_and_signal(const Job& j, const std::string& args, int sig,
                          const std::function<bool()>& signal_when) {
  CliResult r;
  std::thread sender([&] {
    r = run_strand(
        "send job.gcode " + args + " > out.txt & echo $! > '" + j.dir + "/pid.txt'; wait $!",
        j.dir);
  });
  for (int i = 0; i < 2000 && !signal_when(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  std::string pid;
  for (int i = 0; i < 500 && pid.empty(); ++i) {
    pid = slurp(j.dir + "/pid.txt");
    if (pid.empty()) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  // $! is the background list (cd && strand): signal strand, its child (or the list itself
  // when the shell ran strand in its place)
  if (!pid.empty()) {
    const int list = std::stoi(pid);
    std::istringstream in(
        slurp("/proc/" + std::to_string(list) + "/task/" + std::to_string(list) + "/children"));
    bool any = false;
    for (int child = 0; in >> child; any = true) kill(child, sig);
    if (!any) kill(list, sig);
  }
  sender.join();
  return r;
}

// Ctrl-C, SIGTERM and SIGHUP alike: the lines in flight finish, the pen goes up (the
// profile's command), the job can be resumed from the line printed, and the two runs
// together execute the whole file.
class SendSignal : public ::testing::TestWithParam<int> {};

TEST_P(SendSignal, PausesWithThePenUpAndResumes) {
  const Job j = plot_job("xy-plotter-servo");
  std::vector<std::string> first;
  CliResult r;
  {
    FirmwareSim sim(false, {.busy_at = 20});  // command 20 takes 600 ms: the signal lands there
    r = send_and_signal(j, "--port " + sim.port() + " --timeout 0.3 --machine xy-plotter-servo",
                        GetParam(), [&] { return sim.executed().size() >= 20; });
    first = sim.executed();
  }
  EXPECT_EQ(r.exit_code, 130);
  const std::string out = slurp(j.dir + "/out.txt");
  const auto at = out.find("paused         before line ");
  ASSERT_NE(at, std::string::npos) << out;
  EXPECT_EQ(out.find("unconfirmed"), std::string::npos) << out;
  const int line = std::stoi(out.substr(at + 27));
  ASSERT_FALSE(first.empty());
  EXPECT_EQ(first.back(), "M280 P0 S90");  // pen up after the last file command that ran
  const std::size_t ran = first.size() - 1;
  EXPECT_EQ(j.commands[ran].file_line, line);
  const auto all = texts(j.commands);
  EXPECT_EQ(std::vector<std::string>(first.begin(), first.end() - 1),
            std::vector<std::string>(all.begin(), all.begin() + static_cast<long>(ran)));
  FirmwareSim sim(false, {});
  ASSERT_EQ(
      send(j, sim, "--machine xy-plotter-servo --resume-from " + std::to_string(line)).exit_code,
      0);
  const auto done = sim.executed();
  const auto rest = texts(j.commands, ran);
  ASSERT_GE(done.size(), rest.size());
  EXPECT_EQ(std::vector<std::string>(done.end() - static_cast<long>(rest.size()), done.end()),
            rest);
}

INSTANTIATE_TEST_SUITE_P(Signals, SendSignal, ::testing::Values(SIGINT, SIGTERM, SIGHUP),
                         [](const auto& info) {
                           return std::string(info.param == SIGINT    ? "SIGINT"
                                              : info.param == SIGTERM ? "SIGTERM"
                                                                      : "SIGHUP");
                         });

// Ctrl-C while the firmware has fallen silent: a bounded wait for the line in flight, then
// the pen-up line is still sent, and the stop says the line may have run (exit 130, not 1).
TEST(SendCli, InterruptWhileTheFirmwareIsSilentStillSendsTheSafeState) {
  const Job j = plot_job("xy-plotter-servo");
  FirmwareSim sim(false, {.silent_at = 10});
  // --timeout 1: the job would end by itself as "no reply" only after 7 s of silence
  const auto r =
      send_and_signal(j, "--port " + sim.port() + " --timeout 1 --machine xy-plotter-servo", SIGINT,
                      [&] { return sim.received().size() >= 11; });  // M110 N0 + 10 lines
  EXPECT_EQ(r.exit_code, 130) << r.err;
  const auto received = sim.received();
  ASSERT_FALSE(received.empty());
  EXPECT_EQ(received.back(), "M280 P0 S90");  // plain: the firmware's numbering is unknown
  const auto all = texts(j.commands);
  EXPECT_EQ(sim.executed(), std::vector<std::string>(all.begin(), all.begin() + 9));
  const std::string out = slurp(j.dir + "/out.txt");
  EXPECT_NE(out.find("paused         before line " + std::to_string(j.commands[9].file_line)),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("did not confirm line " + std::to_string(j.commands[9].file_line)),
            std::string::npos)
      << out;
}

TEST(SendCli, LostPortStopsWithTheLineToResumeFrom) {
  const Job j = plot_job("xy-plotter-servo");
  FirmwareSim sim(false, {.disconnect_at = 9});
  const auto r = send(j, sim);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("stopped at line " + std::to_string(j.commands[8].file_line)),
            std::string::npos)
      << r.err;
  EXPECT_EQ(sim.executed().size(), 8u);
}

TEST(SendCli, GrblErrorStopsAtTheLineThatFailed) {
  const Job j = plot_job("xy-plotter-grbl");
  FirmwareSim sim(true, {.error_at = 8});
  const auto r = send(j, sim, "--machine xy-plotter-grbl");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("firmware error at line " + std::to_string(j.commands[7].file_line) +
                       ": error:22"),
            std::string::npos)
      << r.err;
  const auto all = texts(j.commands);
  EXPECT_EQ(sim.executed(), std::vector<std::string>(all.begin(), all.begin() + 7));
}

// A hand-written file in a fresh directory, as job.gcode.
Job text_job(const std::string& text) {
  Job j;
  j.dir = fresh_dir("send");
  j.file = j.dir + "/job.gcode";
  slicer::write_file_atomic(j.file, text);
  return j;
}

// Issue 24: "M110 N0" in a file made the sender replay the job from line 1 for ever, "M110 N5"
// made it skip lines and exit 0. Strand owns the numbering: the file's M110 is not sent, and
// the firmware (which takes a numbered M110 as Marlin does) runs every other command once,
// in order.
TEST(SendCli, M110InTheFileNeitherReplaysNorSkipsLines) {
  const std::vector<std::string> want = {"G21", "G90", "G1 X1 Y1 F600", "G1 X2 Y2", "G1 X3 Y3"};
  struct Case {
    const char* text;
    int m110_line;
  };
  for (const Case& c :
       {Case{"M110 N0\nG21\nG90\nG1 X1 Y1 F600\nG1 X2 Y2\nG1 X3 Y3\n", 1},
        Case{"M110 N5\nG21\nG90\nG1 X1 Y1 F600\nG1 X2 Y2\nG1 X3 Y3\n", 1},
        Case{"G21\nG90\nG1 X1 Y1 F600\nM110 N0 ; restart numbering\nG1 X2 Y2\nG1 X3 Y3\n", 4},
        Case{"G21\nG90\nG1 X1 Y1 F600\nG1 X2 Y2\nN99 M110*61\nG1 X3 Y3\n", 5},
        Case{"G21\nG90\nG1 X1 Y1 F600\nG1 X2 Y2\nG1 X3 Y3\nM110 N1000\n", 6}}) {
    SCOPED_TRACE(c.text);
    const Job j = text_job(c.text);
    FirmwareSim sim(false, {});
    const auto r = send(j, sim);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(sim.executed(), want);
    EXPECT_EQ(sim.unrequested_duplicates(), 0);
    EXPECT_EQ(sim.resend_requests(), 0);
    EXPECT_NE(r.out.find("line " + std::to_string(c.m110_line) + ": M110"), std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("sent           5 commands"), std::string::npos) << r.out;
  }
  // GRBL has no M110: it is not sent there either
  const Job j = text_job("M110 N0\nG21\nG90\nG1 X1 Y1 F600\nG1 X2 Y2\nG1 X3 Y3\n");
  FirmwareSim grbl(true, {});
  ASSERT_EQ(send(j, grbl, "--firmware grbl").exit_code, 0);
  EXPECT_EQ(grbl.executed(), want);
}

// Issue 24: a CR-only file went out as one line with CRs inside (resend loop or wrong
// commands). LF, CRLF and CR files, and a mixed one, run exactly their commands.
TEST(SendCli, CrCrlfAndLfFilesRunExactlyTheirCommands) {
  for (const bool grbl : {false, true}) {
    const Job j = plot_job(grbl ? "xy-plotter-grbl" : "xy-plotter-servo");
    const std::string lf = slurp(j.file);
    std::string mixed;
    int n = 0;
    for (char ch : lf)
      mixed += ch == '\n' ? (++n % 3 == 0 ? "\r" : n % 3 == 1 ? "\r\n" : "\n") : std::string(1, ch);
    for (const std::string end : {"\r", "\r\n", "mixed"}) {
      SCOPED_TRACE((grbl ? "grbl, " : "marlin, ") + std::string(end == "\r"      ? "CR"
                                                                : end == "mixed" ? "mixed"
                                                                                 : "CRLF"));
      std::string text = end == "mixed" ? mixed : "";
      if (end != "mixed") {
        for (char ch : lf) text += ch == '\n' ? end : std::string(1, ch);
      }
      slicer::write_file_atomic(j.file, text);
      FirmwareSim sim(grbl, {});
      const auto r = send(j, sim, grbl ? "--firmware grbl" : "");
      ASSERT_EQ(r.exit_code, 0) << r.err;
      EXPECT_EQ(sim.executed(), texts(j.commands));
      EXPECT_EQ(sim.resend_requests(), 0);
    }
  }
}

TEST(SendCli, CharactersThatWouldReachTheControllerAreRefusedBeforeSending) {
  FirmwareSim sim(false, {});
  const Job j = text_job("G21\nG90\nG1 X1\fY2 ; form feed\n");
  expect_input_error(send(j, sim), "job.gcode: line 3");
  slicer::write_file_atomic(j.file, "G21\nM117 done*\n");
  expect_input_error(send(j, sim), "job.gcode: line 2");
  slicer::write_file_atomic(j.file, "G21\nG1 X1 Y1\nG1 X2!\n");
  expect_input_error(send(j, sim, "--firmware grbl"), "line 3: '!' (feed hold)");
  EXPECT_TRUE(sim.received().empty());
}

TEST(SendCli, TimeoutMustBeAFiniteNumberOfSecondsInRange) {
  const Job j = text_job("G21\nG1 X1\n");
  FirmwareSim sim(false, {});
  for (const char* bad : {"nan", "inf", "-inf", "-1", "0", "0.01", "601", "1e300"}) {
    SCOPED_TRACE(bad);
    const auto r = run_strand("send job.gcode --port " + sim.port() + " --timeout " + bad, j.dir);
    expect_input_error(r, "--timeout = ");
    EXPECT_NE(r.err.find("[0.05, 600]"), std::string::npos) << r.err;
  }
  expect_input_error(run_strand("send job.gcode --port " + sim.port() + " --timeout soon", j.dir),
                     "--timeout");
  expect_input_error(run_strand("send job.gcode --port " + sim.port() + " --baud nan", j.dir),
                     "--baud");
  expect_input_error(run_strand("send job.gcode --port " + sim.port() + " --baud -9600", j.dir),
                     "send.baud");
  expect_input_error(
      run_strand("send job.gcode --port " + sim.port() + " --resume-from nan", j.dir),
      "--resume-from");
  expect_input_error(run_strand("send job.gcode --port " + sim.port() + " --resume-from -3", j.dir),
                     "send.resume-from");
  EXPECT_TRUE(sim.received().empty());
}

// Klipper reports a failed command with "!! ..." and then "ok": the job stops there, as on
// Marlin's "Error:", with the line to resume from; nothing after it is sent.
TEST(SendCli, KlipperErrorStopsAtTheLineThatFailed) {
  const Job j = plot_job("xy-plotter-servo");
  FirmwareSim sim(false, {.klipper_error_at = 6});
  const auto r = send(j, sim, "--firmware klipper");
  EXPECT_EQ(r.exit_code, 1);
  const int line = j.commands[5].file_line;
  EXPECT_NE(r.err.find("firmware error at line " + std::to_string(line) + ": !! Move out of range"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("--resume-from " + std::to_string(line)), std::string::npos) << r.err;
  const auto all = texts(j.commands);
  EXPECT_EQ(sim.executed(), std::vector<std::string>(all.begin(), all.begin() + 5));
  EXPECT_EQ(sim.received().size(), 7u);  // M110 N0 and lines 1 to 6
}

// Resuming restores output pins, E mode, the rotary A position and the feed before the rest.
TEST(SendCli, ResumeRestoresOutputsRotaryPositionAndEMode) {
  const Job j = text_job(
      "G21\nG90\nM83\nG92 A0\nM42 P6 S255 ; valve\nG1 X10 Y5 A90 E1 F600\nM42 P6 S0\nM42 P7 S1\n"
      "G1 X20 A180 E1\nG1 X30 E1\n");
  FirmwareSim sim(false, {});
  const auto r = send(j, sim, "--resume-from 10");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto done = sim.executed();
  ASSERT_FALSE(done.empty());
  EXPECT_EQ(done.back(), "G1 X30 E1");
  const std::vector<std::string> preamble(done.begin(), done.end() - 1);
  for (const char* want : {"G21", "G90", "M83", "G0 X20.000 Y5.000 F3000", "G92 E2.00000",
                           "G92 A180.000", "G1 F600", "M42 P6 S0", "M42 P7 S1"}) {
    EXPECT_NE(std::find(preamble.begin(), preamble.end(), want), preamble.end()) << want;
  }
  EXPECT_EQ(std::count(done.begin(), done.end(), "G1 X30 E1"), 1);
}

TEST(SendCli, MissingOrBusyPortsAndNonGcodeFilesAreInputErrors) {
  const Job j = plot_job("xy-plotter-servo");
  expect_input_error(run_strand("send job.gcode --port /dev/nonexistent-strand-port", j.dir),
                     "no such device");
  FirmwareSim sim(false, {});
  const int holder = open(sim.port().c_str(), O_RDWR | O_NOCTTY);
  ASSERT_GE(holder, 0);
  ASSERT_EQ(flock(holder, LOCK_EX | LOCK_NB), 0);
  expect_input_error(send(j, sim), "busy");
  close(holder);
  slicer::write_file_atomic(j.dir + "/notes.gcode", "hello world\n");
  expect_input_error(run_strand("send notes.gcode --port " + sim.port(), j.dir), "is not G-code");
  expect_input_error(
      run_strand("send job.gcode --port " + sim.port() + " --resume-from 999999", j.dir),
      "send.resume-from");
  EXPECT_TRUE(sim.received().empty());  // nothing reached the controller
}

}  // namespace
}  // namespace strand::testing
