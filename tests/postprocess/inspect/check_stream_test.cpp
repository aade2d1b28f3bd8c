#include "postprocess/inspect/check_stream.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "machines/profile.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"
#include "slicer/json_input.h"
#include "slicer/tolerances.h"
#include "tests/support/cli_runner.h"

namespace strand::post {
namespace {

const std::string kDir = std::string(STRAND_SOURCE_DIR) + "/tests/postprocess/inspect/check_stream";

// One line of cases.txt: the outputs of `strand check INPUT FLAGS` captured before the check
// streamed (regenerate.sh), reviewed, stored as NAME.out and NAME.json.
struct Case {
  std::string name, input;
  std::vector<std::string> flags;
};

std::vector<Case> cases() {
  std::ifstream in(kDir + "/cases.txt");
  std::vector<Case> out;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream words(line);
    Case c;
    words >> c.name >> c.input;
    for (std::string w; words >> w;) c.flags.push_back(w);
    out.push_back(c);
  }
  return out;
}

std::string joined(const std::vector<std::string>& flags) {
  std::string s;
  for (const auto& f : flags) s += " " + f;
  return s;
}

// The stored stdout, exit code and stderr of one run, as regenerate.sh writes them.
std::string as_stored(const testing::CliResult& r) {
  return r.out + "--- exit " + std::to_string(r.exit_code) + "\n" + r.err;
}

// The stored stdout alone (what to_text or the JSON prints).
std::string stored_stdout(const std::string& file) {
  const std::string all = testing::slurp(file);
  const std::size_t at = all.rfind("--- exit ");
  return all.substr(0, at);
}

TEST(CheckStream, CasesListEveryStoredOutput) {
  const auto list = cases();
  EXPECT_GE(list.size(), 20u);
  for (const Case& c : list) {
    EXPECT_TRUE(testing::exists(kDir + "/" + c.input)) << c.input;
    EXPECT_TRUE(testing::exists(kDir + "/" + c.name + ".out")) << c.name;
    EXPECT_TRUE(testing::exists(kDir + "/" + c.name + ".json")) << c.name;
  }
}

// The command prints, byte for byte, what it printed when it read files whole.
TEST(CheckStream, CommandPrintsTheStoredOutputs) {
  for (const Case& c : cases()) {
    for (const std::string mode : {"out", "json"}) {
      const std::string args = "check " + c.input + joined(c.flags) + (mode == "json" ? " --json" : "");
      const auto r = testing::run_in_shell(
          "cd '" + kDir + "' && '" + std::string(STRAND_CLI) + "' " + args, testing::fresh_dir("cs"));
      EXPECT_EQ(as_stored(r), testing::slurp(kDir + "/" + c.name + "." + mode)) << "strand " << args;
    }
  }
}

struct CaseSetup {
  CheckOptions options;
  std::unique_ptr<machines::MachineProfile> machine;
};

CaseSetup setup_of(const Case& c) {
  CaseSetup s;
  s.options.touch_mm = slicer::kGcodeResolutionMm;
  for (std::size_t i = 0; i + 1 < c.flags.size(); i += 2) {
    if (c.flags[i] == "--machine")
      s.machine = std::make_unique<machines::MachineProfile>(machines::load_profile(c.flags[i + 1]));
    if (c.flags[i] == "--rules")
      s.options.rules = RulesChoice{check_rules_from_string(c.flags[i + 1]), "given with --rules"};
    if (c.flags[i] == "--arc-tolerance") s.options.arc_tolerance_mm = std::stod(c.flags[i + 1]);
  }
  s.options.machine = s.machine.get();
  return s;
}

// The three ways in agree with the stored output: the file streamed, the text streamed, and
// the whole parsed program (kept for --svg-layer and the preview).
TEST(CheckStream, FileTextAndParsedProgramGiveTheStoredReport) {
  for (const Case& c : cases()) {
    const std::string expected = stored_stdout(kDir + "/" + c.name + ".out");
    if (expected.empty()) continue;  // an input error: the command test covers it
    const std::string expected_json = stored_stdout(kDir + "/" + c.name + ".json");
    const CaseSetup s = setup_of(c);
    const GcodeFile file(kDir + "/" + c.input);
    const CheckReport streamed = check_gcode_file(file, file.scan(), s.options);
    const std::string text = file.text();
    const CheckReport from_text = check_gcode(text, s.options);
    const CheckInput in = read_for_check(text, s.options.machine, s.options.rules);
    CheckOptions with_rules = s.options;
    with_rules.rules = in.rules;
    const CheckReport whole = check_parsed(in.parsed, with_rules);
    for (const CheckReport* r : {&streamed, &from_text, &whole}) {
      EXPECT_EQ(to_text(*r), expected) << c.name;
      EXPECT_EQ(slicer::dump_json(to_json(*r)) + "\n", expected_json) << c.name;
    }
  }
}

struct Pieces {
  std::vector<slicer::Move> moves;
  std::vector<int> lines;
  std::size_t largest = 0, calls = 0;
  bool one_layer_each = true, in_order = true;
};

PieceSink collect(Pieces& p) {
  return [&p](const ParsedGcode& piece, std::size_t first_move) {
    const auto& moves = piece.program.moves;
    ++p.calls;
    p.in_order = p.in_order && first_move == p.moves.size();
    p.largest = std::max<std::size_t>(p.largest, moves.size());
    for (const auto& mv : moves) p.one_layer_each = p.one_layer_each && mv.layer == moves[0].layer;
    p.moves.insert(p.moves.end(), moves.begin(), moves.end());
    p.lines.insert(p.lines.end(), piece.move_lines.begin(), piece.move_lines.end());
  };
}

// parse_gcode_layers hands each layer over once, in order, and the pieces make the moves
// parse_gcode reads, from the text and from the file's lines alike.
TEST(CheckStream, LayersArriveOnceInOrderAsParseGcodeReadsThem) {
  for (const std::string input : {"crossing.gcode", "no_markers.gcode", "pen_servo.gcode",
                                  "../../../data/cura-box-20x20x3.gcode",
                                  "../../../fuzz/seeds/gcode_fuzz/expressions.ngc"}) {
    const GcodeFile file(kDir + "/" + input);
    const std::string text = file.text();
    const ParsedGcode whole = parse_gcode(text);
    const std::vector<slicer::Move> all(whole.program.moves.begin(), whole.program.moves.end());
    Pieces from_text, from_file;
    const ParsedGcode rest = parse_gcode_layers(text, {}, collect(from_text));
    const GcodeScan scan = file.scan();
    EXPECT_EQ(scan.has_o_words, input.ends_with(".ngc")) << input;
    if (!scan.has_o_words) {
      const LineSource lines = [&file](const auto& each) { file.each_line(each); };
      const ParsedGcode rest_of_file = parse_gcode_layers(lines, scan, {}, collect(from_file));
      EXPECT_EQ(from_file.moves, all) << input;
      EXPECT_EQ(rest_of_file.program.layers, whole.program.layers) << input;
    }
    EXPECT_EQ(from_text.moves, all) << input;
    EXPECT_EQ(from_text.lines, whole.move_lines) << input;
    EXPECT_TRUE(from_text.one_layer_each && from_text.in_order) << input;
    EXPECT_TRUE(rest.program.moves.empty()) << input;
    EXPECT_EQ(rest.program.layers, whole.program.layers) << input;
    EXPECT_EQ(rest.program.start_mm, whole.program.start_mm) << input;
    EXPECT_EQ(rest.issues.size(), whole.issues.size()) << input;
  }
}

// Memory holds one layer: on 40 layers of 25 moves no piece is larger than a layer.
TEST(CheckStream, NoPieceHoldsMoreThanOneLayer) {
  std::string g = "G21\nG90\nM83\n";
  for (int l = 0; l < 40; ++l) {
    g += ";LAYER_CHANGE\n;Z:" + std::to_string(0.2 * (l + 1)) + "\nG0 X0 Y0 Z" +
         std::to_string(0.2 * (l + 1)) + "\n";
    for (int k = 1; k < 25; ++k) g += "G1 X" + std::to_string(k) + " Y" + std::to_string(k % 2) + " E0.1\n";
  }
  Pieces p;
  parse_gcode_layers(g, {}, collect(p));
  EXPECT_EQ(p.moves.size(), 40u * 25u);
  EXPECT_EQ(p.largest, 25u);
  EXPECT_EQ(p.calls, 41u);  // one per layer change and one at the end
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  for (std::size_t pos = 0; pos <= text.size();) {
    std::size_t nl = text.find('\n', pos);
    if (nl == std::string::npos) nl = text.size();
    out.push_back(text.substr(pos, nl - pos));
    pos = nl + 1;
  }
  return out;
}

// Lines split across the 1 MiB buffer, longer than it, with CR, and a last line without
// '\n' come out as the text splits them.
TEST(GcodeFile, LinesCrossBufferEdgesIntact) {
  std::string text = "G21\r\n;" + std::string(3'000'000, 'x') + "\n";
  for (int i = 0; text.size() < 5'000'000; ++i) text += "G1 X" + std::to_string(i) + " Y1\n";
  text += "G1 X9 Y9";  // no newline
  const std::string dir = testing::fresh_dir("gcode-file");
  slicer::write_file_atomic(dir + "/big.gcode", text);
  const GcodeFile file(dir + "/big.gcode");
  std::vector<std::string> seen;
  std::uintmax_t read = 0;
  file.each_line([&seen](std::string_view l) { seen.emplace_back(l); },
                 [&read](std::uintmax_t bytes) { read = bytes; });
  EXPECT_EQ(seen, lines_of(text));
  EXPECT_EQ(read, text.size());
  EXPECT_EQ(file.size_bytes(), text.size());
}

TEST(GcodeFile, RefusesWhatReadFileRefuses) {
  const std::string dir = testing::fresh_dir("gcode-file-bad");
  for (const std::string& path : {dir + "/missing.gcode", dir}) {
    std::string mine, theirs;
    try {
      GcodeFile f(path);
    } catch (const InputError& e) {
      mine = e.what();
    }
    try {
      slicer::read_file(path);
    } catch (const InputError& e) {
      theirs = e.what();
    }
    EXPECT_FALSE(mine.empty()) << path;
    EXPECT_EQ(mine, theirs) << path;
  }
}

// A malformed line of any length is quoted short: the report keeps a bounded text per issue.
TEST(CheckStream, MalformedHugeLineIsQuotedShort) {
  const std::string huge = "G1 X1 Y" + std::string(100'000, '?');
  const CheckReport r = check_gcode("G1 X0 Y0 E1\n" + huge + "\n", {});
  ASSERT_EQ(r.parse_issues.size(), 1u);
  EXPECT_LT(r.parse_issues[0].what.size(), 300u);
  EXPECT_NE(r.parse_issues[0].what.find("'G1 X1 Y???"), std::string::npos);
  EXPECT_NE(r.parse_issues[0].what.find("...'"), std::string::npos);
}

}  // namespace
}  // namespace strand::post
