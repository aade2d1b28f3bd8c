// The send parser: line ends (LF, CRLF, CR), a file's own serial framing, characters that
// must never reach a controller, the file's M110 lines and Klipper's "!!" errors.
#include "machines/send/protocol.h"

#include <gtest/gtest.h>

#include "slicer/input_error.h"

namespace strand::machines {
namespace {

std::vector<std::string> texts(const std::vector<Command>& c) {
  std::vector<std::string> out;
  for (const auto& x : c) out.push_back(x.text);
  return out;
}

std::vector<int> lines(const std::vector<Command>& c) {
  std::vector<int> out;
  for (const auto& x : c) out.push_back(x.file_line);
  return out;
}

TEST(Protocol, LfCrlfAndCrEndLinesAlike) {
  const std::vector<std::string> want = {"G21", "G90", "G1 X1 Y2", "M280 P0 S30"};
  for (const std::string end : {"\n", "\r\n", "\r"}) {
    const std::string text =
        "G21" + end + "G90 ; abs" + end + end + "G1 X1 Y2" + end + "M280 P0 S30";
    const auto c = commands_of(text, "f");
    EXPECT_EQ(texts(c), want) << "line end " << (end == "\r" ? "CR" : end == "\n" ? "LF" : "CRLF");
    EXPECT_EQ(lines(c), (std::vector<int>{1, 2, 4, 5}));
  }
  // mixed in one file: each CR, LF and CRLF is one line end; CR CR LF is two
  const auto c = commands_of("G21\rG90\r\nG1 X1\nG1 X2\r\r\nG1 X3\n\rG1 X4", "f");
  EXPECT_EQ(texts(c), (std::vector<std::string>{"G21", "G90", "G1 X1", "G1 X2", "G1 X3", "G1 X4"}));
  EXPECT_EQ(lines(c), (std::vector<int>{1, 2, 3, 4, 6, 8}));
}

TEST(Protocol, AFilesOwnLineNumbersAndChecksumsAreRemoved) {
  const auto c = commands_of("N10 G1 X5*57\nN11 M280 P0 S30 *12\nN12\nG1 Y2\n", "f");
  EXPECT_EQ(texts(c), (std::vector<std::string>{"G1 X5", "M280 P0 S30", "G1 Y2"}));
  EXPECT_EQ(lines(c), (std::vector<int>{1, 2, 4}));
  EXPECT_THROW(commands_of("G1 Y2*3\n", "f"), InputError);  // a checksum needs its line number
}

TEST(Protocol, ControlCharactersAndStarsInsideACommandAreRefusedWithTheLine) {
  const auto message = [](const std::string& text) {
    try {
      commands_of(text, "f.gcode");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message("G21\nG1 X1\fY2\n").find("f.gcode: line 2"), std::string::npos);
  EXPECT_NE(message("G21\nG1 X1\fY2\n").find("0x0c"), std::string::npos);
  EXPECT_NE(message("G1 X1\x1b[2J\n").find("control character 0x1b"), std::string::npos);
  EXPECT_NE(message("G21\nG90\nM117 3*4\n").find("line 3"), std::string::npos);
  EXPECT_NE(message("G21\nG90\nM117 3*4\n").find("'*'"), std::string::npos);
  EXPECT_EQ(message("G1\tX1 ; tab is a space\n"), "accepted");
  EXPECT_EQ(message("G1 X1 ; comments may hold *, \x01 and \xc3\xa9\n"), "accepted");
}

TEST(Protocol, M110InAFileIsRecognised) {
  for (const char* yes : {"M110", "M110 N0", "m110n5", "M110 N12345", "M 110"})
    EXPECT_TRUE(sets_line_number(yes)) << yes;
  for (const char* no : {"M11", "M1100", "M110.5", "G1 X110", "M111 S0", "N110"})
    EXPECT_FALSE(sets_line_number(no)) << no;
}

TEST(Protocol, GrblRealtimeCharactersInACommandAreRefused) {
  for (const std::string c : {"G1 X1!", "G1 X1 ~", "$J=X1?", "G1 X1\xc2\x85"}) {
    try {
      refuse_grbl_realtime_characters({{1, "G21"}, {3, c}}, "f.gcode");
      ADD_FAILURE() << c << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("f.gcode: line 3"), std::string::npos) << e.what();
    }
  }
  EXPECT_NO_THROW(refuse_grbl_realtime_characters({{1, "G1 X1 Y2 F300"}, {2, "$H"}}, "f"));
}

TEST(Protocol, KlipperErrorLinesAreErrors) {
  for (Firmware f : {Firmware::Klipper, Firmware::Marlin, Firmware::RepRap}) {
    EXPECT_EQ(parse_reply("!! Move out of range: 300.000 0.000 0.000 [0.000]", f).kind,
              ReplyKind::Error);
    EXPECT_EQ(parse_reply("!! Shutdown due to webhooks request", f).kind, ReplyKind::Error);
  }
  EXPECT_EQ(parse_reply("// Klipper state: Ready", Firmware::Klipper).kind, ReplyKind::Other);
}

}  // namespace
}  // namespace strand::machines
