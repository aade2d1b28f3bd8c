// `strand send` against a simulated firmware on a pseudo-terminal: under every fault the
// controller executes exactly the file's commands in order, nothing skipped and nothing
// sent twice unless it asked for a resend; errors and lost ports stop with a line to resume
// from, and resuming finishes the job; bad ports and files exit 2 with one line.
#include <gtest/gtest.h>
#include <sys/file.h>
#include <fcntl.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
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
  const auto r = run_strand("plot '" + kSamples + "layers.svg' --machine " + machine + " --fit 100x60 -o job.gcode", j.dir);
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
    EXPECT_NE(r.err.find("firmware error at line " + std::to_string(line) + ": Error:Printer halted"), std::string::npos) << r.err;
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
  const std::vector<std::string> preamble(done.begin(), done.end() - static_cast<long>(rest.size()));
  ASSERT_GE(preamble.size(), 3u);
  EXPECT_EQ(preamble[0], "G21");
  EXPECT_EQ(preamble[1], "G90");
  EXPECT_EQ(preamble[2], "M280 P0 S90");
  EXPECT_EQ(std::vector<std::string>(done.end() - static_cast<long>(rest.size()), done.end()), rest);
}

// Ctrl-C: the lines in flight finish, the pen goes up (the profile's command), the job
// can be resumed from the line printed, and the two runs together execute the whole file.
TEST(SendCli, InterruptPausesWithThePenUpAndResumes) {
  const Job j = plot_job("xy-plotter-servo");
  std::vector<std::string> first;
  CliResult r;
  {
    FirmwareSim sim(false, {.busy_at = 20});  // command 20 takes 600 ms: the interrupt lands there
    std::thread sender([&] {
      r = run_strand("send job.gcode --port " + sim.port() + " --timeout 0.3 --machine xy-plotter-servo > out.txt & "
                     "echo $! > '" + j.dir + "/pid.txt'; wait $!", j.dir);
    });
    // interrupt once the controller is inside command 20 (bounded wait: 20 s)
    for (int i = 0; i < 2000 && sim.executed().size() < 20; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    const std::string pid = slurp(j.dir + "/pid.txt");
    // $! is the background list (cd && strand): interrupt it and its children, as a
    // terminal's Ctrl-C reaches the whole foreground group
    if (!pid.empty()) {
      std::string children = slurp("/proc/" + std::to_string(std::stoi(pid)) + "/task/" + std::to_string(std::stoi(pid)) + "/children");
      kill(std::stoi(pid), SIGINT);
      std::istringstream in(children);
      for (int child = 0; in >> child;) kill(child, SIGINT);
    }
    sender.join();
    first = sim.executed();
  }
  EXPECT_EQ(r.exit_code, 130);
  const std::string out = slurp(j.dir + "/out.txt");
  const auto at = out.find("paused         before line ");
  ASSERT_NE(at, std::string::npos) << out;
  const int line = std::stoi(out.substr(at + 27));
  ASSERT_FALSE(first.empty());
  EXPECT_EQ(first.back(), "M280 P0 S90");  // pen up after the last file command that ran
  const std::size_t ran = first.size() - 1;
  EXPECT_EQ(j.commands[ran].file_line, line);
  const auto all = texts(j.commands);
  EXPECT_EQ(std::vector<std::string>(first.begin(), first.end() - 1),
            std::vector<std::string>(all.begin(), all.begin() + static_cast<long>(ran)));
  FirmwareSim sim(false, {});
  ASSERT_EQ(send(j, sim, "--machine xy-plotter-servo --resume-from " + std::to_string(line)).exit_code, 0);
  const auto done = sim.executed();
  const auto rest = texts(j.commands, ran);
  ASSERT_GE(done.size(), rest.size());
  EXPECT_EQ(std::vector<std::string>(done.end() - static_cast<long>(rest.size()), done.end()), rest);
}

TEST(SendCli, LostPortStopsWithTheLineToResumeFrom) {
  const Job j = plot_job("xy-plotter-servo");
  FirmwareSim sim(false, {.disconnect_at = 9});
  const auto r = send(j, sim);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("stopped at line " + std::to_string(j.commands[8].file_line)), std::string::npos) << r.err;
  EXPECT_EQ(sim.executed().size(), 8u);
}

TEST(SendCli, GrblErrorStopsAtTheLineThatFailed) {
  const Job j = plot_job("xy-plotter-grbl");
  FirmwareSim sim(true, {.error_at = 8});
  const auto r = send(j, sim, "--machine xy-plotter-grbl");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("firmware error at line " + std::to_string(j.commands[7].file_line) + ": error:22"), std::string::npos) << r.err;
  const auto all = texts(j.commands);
  EXPECT_EQ(sim.executed(), std::vector<std::string>(all.begin(), all.begin() + 7));
}

TEST(SendCli, MissingOrBusyPortsAndNonGcodeFilesAreInputErrors) {
  const Job j = plot_job("xy-plotter-servo");
  expect_input_error(run_strand("send job.gcode --port /dev/nonexistent-strand-port", j.dir), "no such device");
  FirmwareSim sim(false, {});
  const int holder = open(sim.port().c_str(), O_RDWR | O_NOCTTY);
  ASSERT_GE(holder, 0);
  ASSERT_EQ(flock(holder, LOCK_EX | LOCK_NB), 0);
  expect_input_error(send(j, sim), "busy");
  close(holder);
  slicer::write_file_atomic(j.dir + "/notes.gcode", "hello world\n");
  expect_input_error(run_strand("send notes.gcode --port " + sim.port(), j.dir), "is not G-code");
  expect_input_error(run_strand("send job.gcode --port " + sim.port() + " --resume-from 999999", j.dir), "send.resume-from");
  EXPECT_TRUE(sim.received().empty());  // nothing reached the controller
}

}  // namespace
}  // namespace strand::testing
