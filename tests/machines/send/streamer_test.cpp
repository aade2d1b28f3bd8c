// The streaming state machine without a port: Marlin's numbered ping-pong, resend and probe
// rules, GRBL's character counting, replies, G-code extraction and the resume state.
#include "machines/send/streamer.h"

#include <gtest/gtest.h>

#include "machines/send/resume.h"
#include "slicer/input_error.h"

namespace strand::machines {
namespace {

std::vector<Command> cmds(int n) {
  std::vector<Command> c;
  for (int i = 1; i <= n; ++i) c.push_back({10 + i, "G1 X" + std::to_string(i)});
  return c;
}

TEST(Protocol, ChecksumIsTheXorOfTheFramedLine) {
  // XOR of "N1 G28": 'N'^'1'^' '^'G'^'2'^'8'
  int x = 0;
  for (char c : std::string("N1 G28")) x ^= c;
  EXPECT_EQ(numbered(1, "G28"), "N1 G28*" + std::to_string(x));
}

TEST(Protocol, CommandsKeepTheirFileLinesAndLoseComments) {
  const auto c = commands_of("; header\n\nG21 ; mm\n(setup) G90\nM280 P0 S30 ; pen down\n", "f");
  ASSERT_EQ(c.size(), 3u);
  EXPECT_EQ(c[0], (Command{3, "G21"}));
  EXPECT_EQ(c[1], (Command{4, "G90"}));
  EXPECT_EQ(c[2], (Command{5, "M280 P0 S30"}));
  EXPECT_THROW(commands_of("hello world\n", "f"), InputError);
  EXPECT_THROW(commands_of(std::string("G1\0X", 4), "f"), InputError);
  EXPECT_THROW(commands_of("; only a comment\n", "f"), InputError);
}

TEST(Protocol, RepliesAreClassified) {
  EXPECT_EQ(parse_reply("ok T:20.0", Firmware::Marlin).kind, ReplyKind::Ok);
  const Reply r = parse_reply("Resend: 17", Firmware::Marlin);
  EXPECT_EQ(r.kind, ReplyKind::Resend);
  EXPECT_EQ(r.line, 17);
  EXPECT_EQ(parse_reply("rs 4", Firmware::RepRap).line, 4);
  EXPECT_EQ(parse_reply("echo:busy: processing", Firmware::Marlin).kind, ReplyKind::Busy);
  EXPECT_EQ(parse_reply("Error:checksum mismatch, Last Line: 3", Firmware::Marlin).kind,
            ReplyKind::LineError);
  EXPECT_EQ(parse_reply("Error:Printer halted. kill() called!", Firmware::Marlin).kind,
            ReplyKind::Error);
  EXPECT_EQ(parse_reply("error:22", Firmware::Grbl).kind, ReplyKind::Error);
  EXPECT_EQ(parse_reply("ALARM:1", Firmware::Grbl).kind, ReplyKind::Alarm);
  EXPECT_TRUE(parse_reply("<Idle|MPos:0,0,0>", Firmware::Grbl).idle);
  EXPECT_EQ(parse_reply("Grbl 1.1h ['$' for help]", Firmware::Grbl).kind, ReplyKind::Restart);
}

TEST(Streamer, MarlinSendsOneNumberedLineAtATime) {
  Streamer s(Firmware::Marlin, cmds(3));
  EXPECT_EQ(s.next_write(), "M110 N0\n");
  EXPECT_EQ(s.next_write(), "");  // waits for the reset's ok
  s.on_line("ok");
  EXPECT_EQ(s.next_write(), numbered(1, "G1 X1") + "\n");
  EXPECT_EQ(s.next_write(), "");
  s.on_line("ok");
  EXPECT_EQ(s.acknowledged(), 1u);
  EXPECT_EQ(s.next_write(), numbered(2, "G1 X2") + "\n");
  // a resend request rewinds; its trailing ok acknowledges nothing
  s.on_line("Error:checksum mismatch, Last Line: 1");
  s.on_line("Resend: 2");
  EXPECT_EQ(s.next_write(), "");
  s.on_line("ok");
  EXPECT_EQ(s.acknowledged(), 1u);
  EXPECT_EQ(s.next_write(), numbered(2, "G1 X2") + "\n");
  s.on_line("ok");
  EXPECT_EQ(s.next_write(), numbered(3, "G1 X3") + "\n");
  // silence: probe with M105 (never the line again); its ok proves line 3 ran
  EXPECT_EQ(s.on_silence(), "M105\n");
  s.on_line("ok T:20.0");
  EXPECT_EQ(s.state(), StreamState::Done);
}

TEST(Streamer, AProbeAnsweredForALostLineIsCorrectedByTheResend) {
  Streamer s(Firmware::Marlin, cmds(3));
  s.next_write();
  s.on_line("ok");
  s.next_write();  // N1, lost on the wire
  EXPECT_EQ(s.on_silence(), "M105\n");
  s.on_line("ok");  // M105's ok: line 1 looks done
  EXPECT_EQ(s.next_write(), numbered(2, "G1 X2") + "\n");
  s.on_line("Error:Line Number is not Last Line Number+1, Last Line: 0");
  s.on_line("Resend: 1");
  s.on_line("ok");
  EXPECT_EQ(s.acknowledged(), 0u);
  EXPECT_EQ(s.next_write(), numbered(1, "G1 X1") + "\n");
}

TEST(Streamer, FatalErrorStopsAtTheLineInFlight) {
  Streamer s(Firmware::Marlin, cmds(3));
  s.next_write();
  s.on_line("ok");
  s.next_write();
  s.on_line("ok");
  s.next_write();  // N2
  s.on_line("Error:Printer halted. kill() called!");
  EXPECT_EQ(s.state(), StreamState::Failed);
  EXPECT_EQ(s.resume_line(), 12);  // file line of the second command
  EXPECT_EQ(s.failure(), "Error:Printer halted. kill() called!");
}

TEST(Streamer, GrblFillsItsBufferByCharacterCounting) {
  std::vector<Command> c;
  for (int i = 0; i < 20; ++i) c.push_back({i + 1, "G1 X100.000 Y100.000"});  // 21 bytes with \n
  Streamer s(Firmware::Grbl, c);
  const std::string first = s.next_write();
  EXPECT_EQ(first.size(), 6u * 21u);  // 126 <= 127 < 147
  EXPECT_EQ(s.next_write(), "");
  s.on_line("ok");
  EXPECT_EQ(s.next_write().size(), 21u);
  EXPECT_EQ(s.on_silence(), "?");
  s.on_line("<Idle|MPos:0,0,0>");  // idle: everything sent has run
  EXPECT_EQ(s.acknowledged(), 7u);
}

TEST(Streamer, PauseWaitsForTheLinesInFlight) {
  Streamer s(Firmware::Marlin, cmds(5));
  s.next_write();
  s.on_line("ok");
  s.next_write();
  s.pause();
  EXPECT_EQ(s.state(), StreamState::Running);
  s.on_line("ok");
  EXPECT_EQ(s.state(), StreamState::Paused);
  EXPECT_EQ(s.next_write(), "");
  EXPECT_EQ(s.resume_line(), 12);
}

// The numbering is the streamer's: a file's M110 is never sent, whatever its N.
TEST(Streamer, AFilesM110IsLeftOutOfTheNumbering) {
  for (const char* reset : {"M110 N0", "M110 N5", "M110"}) {
    Streamer s(Firmware::Marlin, {{1, "G1 X1"}, {2, reset}, {3, "G1 X2"}});
    EXPECT_EQ(s.total(), 2u);
    EXPECT_EQ(s.next_write(), "M110 N0\n");
    s.on_line("ok");
    EXPECT_EQ(s.next_write(), numbered(1, "G1 X1") + "\n");
    s.on_line("ok");
    EXPECT_EQ(s.next_write(), numbered(2, "G1 X2") + "\n");
    s.on_line("ok");
    EXPECT_EQ(s.state(), StreamState::Done);
  }
}

// A resend request for a line never sent means the firmware's numbering is not ours: the
// "ok" after it would otherwise acknowledge a line that did not run.
TEST(Streamer, AResendForALineNeverSentStopsTheJob) {
  Streamer s(Firmware::Marlin, cmds(5));
  s.next_write();
  s.on_line("ok");
  s.next_write();  // N1
  s.on_line("ok");
  s.next_write();  // N2
  s.on_line("Error:Line Number is not Last Line Number+1, Last Line: 5");
  s.on_line("Resend: 6");
  s.on_line("ok");
  EXPECT_EQ(s.state(), StreamState::Failed);
  EXPECT_EQ(s.acknowledged(), 1u);
  EXPECT_EQ(s.resume_line(), 12);
  EXPECT_NE(s.failure().find("asked for line 6"), std::string::npos) << s.failure();
}

TEST(Streamer, EndlessResendRequestsStopTheJob) {
  Streamer s(Firmware::Marlin, cmds(3));
  s.next_write();
  s.on_line("ok");
  int sent = 0;
  while (s.state() == StreamState::Running && sent < 1000) {
    if (!s.next_write().empty()) ++sent;
    s.on_line("Error:checksum mismatch, Last Line: 0");
    s.on_line("Resend: 1");
    s.on_line("ok");
  }
  EXPECT_EQ(s.state(), StreamState::Failed);
  EXPECT_EQ(sent, kMaxResendsWithoutProgress + 1);
  EXPECT_EQ(s.resume_line(), 11);
}

TEST(Streamer, KlipperErrorStopsAtTheLineInFlight) {
  Streamer s(Firmware::Klipper, cmds(3));
  s.next_write();
  s.on_line("ok");
  s.next_write();
  s.on_line("ok");
  s.next_write();  // N2
  s.on_line("!! Move out of range: 300.000 0.000 0.000 [0.000]");
  s.on_line("ok");
  EXPECT_EQ(s.state(), StreamState::Failed);
  EXPECT_EQ(s.acknowledged(), 1u);
  EXPECT_EQ(s.resume_line(), 12);
}

TEST(Resume, ModalStateBeforeALineAndItsPreamble) {
  const auto c = commands_of(
      "G21\nG90\nM280 P0 S30\nG1 X10 Y20 Z0.4 F1200\nG91\nG1 X5\nG90\nG1 X30 Y40\n", "f");
  const auto m = load_profile("xy-plotter-servo");
  const ModalState s = modal_state_before(c, 8, m);
  EXPECT_EQ(s.x, 15.0);
  EXPECT_EQ(s.y, 20.0);
  EXPECT_EQ(s.z, 0.4);
  EXPECT_EQ(s.f, 1200.0);
  EXPECT_FALSE(s.relative);
  EXPECT_EQ(s.tool_state, std::vector<std::string>{"M280 P0 S30"});
  const auto p = resume_preamble(m, s);
  EXPECT_EQ(p, (std::vector<std::string>{"G21", "G90", "M280 P0 S90 ; pen up",
                                         "G0 X15.000 Y20.000 F6000", "G1 F1200", "M280 P0 S30"}));
}

TEST(Resume, ValveMachinesCloseTheValveToPause) {
  const auto m = load_profile("deltawasp-2040-clay-valve");
  const auto safe = safe_state_gcode(m, {});
  EXPECT_EQ(safe, m.deposition.off_gcode);
  EXPECT_FALSE(safe.empty());
}

}  // namespace
}  // namespace strand::machines
