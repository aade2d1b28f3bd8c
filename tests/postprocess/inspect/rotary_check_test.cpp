// Tampered rotary-axis G-code: each change is found on its line (issue 24), as pose CSVs are
// in pose_check_test.
#include "postprocess/inspect/pose_check.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <sstream>

#include "machines/pose_csv.h"
#include "patterns/registry.h"
#include "postprocess/plan/produce_curved.h"
#include "slicer/input_error.h"
#include "slicer/units.h"
#include "tests/support/cli_runner.h"
#include "tests/support/sample_jobs.h"
#include "tests/postprocess/inspect/curved_file_edits.h"

namespace strand::post {
namespace {

using namespace curved_edits;

// --- Rotary G-code ---

const std::string& rotary_gcode() {
  static const std::string g = produced_main("scaffold-cylinder-rotary.json", "r.gcode");
  return g;
}

const machines::MachineProfile& rotary_machine() {
  static const auto m = machines::load_profile("marlin-rotary-a");
  return m;
}

// 0-based line index of the n-th deposit line (G1 with E) after the marker.
std::size_t deposit_line(const std::string& g, const std::string& after, int nth) {
  std::size_t line = static_cast<std::size_t>(
      std::count(g.begin(), g.begin() + static_cast<std::ptrdiff_t>(g.find(after)), '\n'));
  for (int k = 0;; ++line) {
    const std::string l = line_at(g, line);
    if (l.rfind("G1 ", 0) == 0 && l.find(" E") != std::string::npos && ++k > nth) return line;
  }
}

// Replaces the number after ` <letter>` on a line by f(number).
std::string with_word(std::string g, std::size_t line, char letter,
                      const std::function<double(double)>& f) {
  const std::size_t at = line_start(g, line);
  const std::size_t end = g.find('\n', at);
  const std::size_t w = g.find(std::string(" ") + letter, at);
  if (w == std::string::npos || w > end) {
    ADD_FAILURE() << "no " << letter << " on line " << line;
    return g;
  }
  const std::size_t num_end = g.find_first_of(" \n", w + 2);
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.3f", f(std::stod(g.substr(w + 2, num_end - w - 2))));
  return g.replace(w + 2, num_end - w - 2, buf);
}

bool names_line(const PoseCheckReport& r, std::size_t line0) {  // 0-based index
  for (const PoseFindings* f : {&r.extrusion, &r.speed, &r.numbering, &r.off_surface})
    if (names_row(*f, line0 + 1)) return true;
  return false;
}

TEST(RotaryCheckTampering, AnUntouchedFilePasses) {
  const auto r = check_rotary_gcode(rotary_gcode(), "r.gcode", &rotary_machine());
  EXPECT_TRUE(r.ok()) << to_text(r);
  // Without --machine the header names the machine whose feeds it was planned with.
  const auto alone = check_rotary_gcode(rotary_gcode(), "r.gcode", nullptr);
  EXPECT_TRUE(alone.ok()) << to_text(alone);
}

TEST(RotaryCheckTampering, AnAShiftOnOneLineIsFoundThere) {
  const std::size_t line = deposit_line(rotary_gcode(), ";LAYER:1", 40);
  const std::string g = with_word(rotary_gcode(), line, 'A', [](double a) { return a + 20; });
  const auto r = check_rotary_gcode(g, "r.gcode", &rotary_machine());
  EXPECT_FALSE(r.ok());
  EXPECT_TRUE(names_line(r, line)) << to_text(r);
}

TEST(RotaryCheckTampering, EveryAShiftedAlikeMovesThePatchOffItsCentre) {
  std::string g;
  std::istringstream in(rotary_gcode());
  for (std::string l; std::getline(in, l);) {
    const std::size_t a = l.find(" A");
    if ((l.rfind("G0 ", 0) == 0 || l.rfind("G1 ", 0) == 0) && a != std::string::npos) {
      const std::size_t end = l.find(' ', a + 2);
      char buf[40];
      std::snprintf(buf, sizeof buf, "%.3f", std::stod(l.substr(a + 2, end - a - 2)) + 20);
      l.replace(a + 2, end == std::string::npos ? std::string::npos : end - a - 2, buf);
    }
    g += l + "\n";
  }
  const auto r = check_rotary_gcode(g, "r.gcode", &rotary_machine());
  EXPECT_FALSE(r.ok());
  EXPECT_NE(to_text(r).find("20.000 deg of A"), std::string::npos) << to_text(r);
}

TEST(RotaryCheckTampering, FeedsTimesFiveAreFound) {
  const std::string& g0 = rotary_gcode();
  const std::size_t line = deposit_line(g0, ";LAYER:2", 10);
  const auto one = check_rotary_gcode(with_word(g0, line, 'F', [](double f) { return 5 * f; }),
                                      "r.gcode", &rotary_machine());
  EXPECT_TRUE(names_row(one.speed, line + 1)) << to_text(one);
  // Every feed of the file times five: the planned speeds (the job's and the machine's) differ.
  std::string all;
  std::istringstream in(g0);
  for (std::string l; std::getline(in, l);) {
    const std::size_t f = l.find(" F");
    if ((l.rfind("G1 ", 0) == 0 || l.rfind("G0 ", 0) == 0) && f != std::string::npos) {
      const std::size_t end = l.find(' ', f + 2);
      const double v = std::stod(l.substr(f + 2, end - f - 2));
      char buf[40];
      std::snprintf(buf, sizeof buf, "%.3f", 5 * v);
      l.replace(f + 2, end == std::string::npos ? std::string::npos : end - f - 2, buf);
    }
    all += l + "\n";
  }
  const auto every = check_rotary_gcode(all, "r.gcode", &rotary_machine());
  EXPECT_FALSE(every.ok());
  EXPECT_GE(every.speed.total, 1u);
  EXPECT_NE(to_text(every).find("planned"), std::string::npos) << to_text(every);
  EXPECT_FALSE(check_rotary_gcode(all, "r.gcode", nullptr).ok()) << "machine from the header";
}

TEST(RotaryCheckTampering, ADeletedOrSwappedLineIsFoundThere) {
  const std::string& g = rotary_gcode();
  const std::size_t line = deposit_line(g, ";LAYER:0", 60);
  const auto deleted = check_rotary_gcode(without_line(g, line), "r.gcode", &rotary_machine());
  EXPECT_FALSE(deleted.ok());
  EXPECT_TRUE(names_line(deleted, line)) << to_text(deleted);  // the next line moved up
  std::string swapped = g;
  const std::string a = line_at(g, line), b = line_at(g, line + 1);
  swapped.replace(line_start(g, line), a.size() + b.size(), b + a);
  const auto s = check_rotary_gcode(swapped, "r.gcode", &rotary_machine());
  EXPECT_FALSE(s.ok());
  EXPECT_TRUE(names_line(s, line) || names_line(s, line + 1)) << to_text(s);
}

TEST(RotaryCheckTampering, RenumberedLayersAndEmptyFilesAreFound) {
  const std::string& g = rotary_gcode();
  std::string renumbered = g;
  renumbered.replace(renumbered.find(";LAYER:2"), 8, ";LAYER:5");
  const auto r = check_rotary_gcode(renumbered, "r.gcode", &rotary_machine());
  EXPECT_FALSE(r.ok());
  EXPECT_NE(to_text(r).find(";LAYER:5 is the file's layer 2"), std::string::npos) << to_text(r);
  const std::string header = g.substr(0, g.find("G21"));
  EXPECT_THROW(check_rotary_gcode(header, "r.gcode", &rotary_machine()), InputError);
}

}  // namespace
}  // namespace strand::post
