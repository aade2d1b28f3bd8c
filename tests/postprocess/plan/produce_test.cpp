// Every generator with every DIW profile: the G-code parses back, carries the right flow
// words for the machine's deposition model, and deposits the geometric bead volume.
#include "postprocess/plan/produce.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <charconv>
#include <iostream>
#include <sstream>

#include "patterns/registry.h"
#include "postprocess/plan/estimate.h"
#include "postprocess/inspect/gcode_parser.h"
#include "slicer/input_error.h"
#include "tests/support/sample_jobs.h"

namespace strand::post {
namespace {

using machines::DepositionModel;

// Each generator's sample job (samples/*.json; samples_test requires one per generator).
std::optional<slicer::Toolpath> sample_toolpath(const patterns::GeneratorSpec& g) {
  const auto it = testing::sample_params().find(g.name);
  if (it == testing::sample_params().end()) {
    ADD_FAILURE() << "generator " << g.name << " has no sample job in samples/";
    return std::nullopt;
  }
  return g.generate(slicer::resolve_params(g.table(), it->second));
}

// Printers (not pen plotters) with any deposition model.
// Flat DIW printers; robot cells and rotary printers print on cylinders (produce_curved).
bool is_diw(const machines::MachineProfile& m) {
  return !m.plotter.enabled && !m.robot.enabled && !m.rotary.enabled;
}

double geometric_volume_mm3(const slicer::Toolpath& t) {
  double v = 0.0;
  for (const auto& l : t.layers) {
    for (const auto& s : l.strokes) v += slicer::stroke_length(s) * slicer::bead_area_mm2(s.width_mm, s.height_mm);
  }
  return v;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

bool has_xy(const std::string& l) { return l.find(" X") != std::string::npos || l.find(" Y") != std::string::npos; }

// Sum of E words on moves that go somewhere (relative E): deposits only, not prime/retract.
double deposit_e(const std::string& gcode) {
  double sum = 0.0;
  for (const auto& l : lines_of(gcode)) {
    const auto at = l.find(" E");
    const bool deposit = l.starts_with("G1") || l.starts_with("G2") || l.starts_with("G3");
    if (!deposit || at == std::string::npos || !has_xy(l)) continue;
    double e = 0.0;
    std::from_chars(l.data() + at + 2, l.data() + l.size(), e);
    sum += e;
  }
  return sum;
}

// Valve lines bracket every strand (run of G1/G2/G3 between G0s): open before its first
// deposit, closed before the next travel, each command right after M400.
void expect_valve_brackets(const std::string& gcode, const machines::MachineProfile& m) {
  // From the first layer to the end template (start/end templates may set the valve idle).
  const auto all = lines_of(gcode);
  auto first = std::find(all.begin(), all.end(), ";LAYER_CHANGE");
  auto last = std::find(first, all.end(), ";TYPE:Custom");
  const std::vector<std::string> ls(first, last);
  bool open = false;
  int strands = 0, opens = 0;
  bool in_strand = false;
  for (std::size_t i = 0; i < ls.size(); ++i) {
    const std::string& l = ls[i];
    if (l == m.deposition.on_gcode.front() || l == m.deposition.off_gcode.front()) {
      ASSERT_GT(i, 0u);
      EXPECT_EQ(ls[i - 1] == "M400" || ls[i - 1].starts_with("M400"), true) << "line " << i;
      open = l == m.deposition.on_gcode.front();
      opens += open ? 1 : 0;
      continue;
    }
    if (l.starts_with("G0")) {
      EXPECT_FALSE(open) << "travel with the valve open at line " << i + 1 << ": " << l;
      in_strand = false;
    } else if ((l.starts_with("G1") || l.starts_with("G2") || l.starts_with("G3")) && has_xy(l) && !in_strand) {
      EXPECT_TRUE(open) << "strand starts with the valve closed at line " << i + 1;
      in_strand = true;
      ++strands;
    }
  }
  EXPECT_FALSE(open) << "valve left open at the end";
  EXPECT_EQ(opens, strands);
}

void check_one(const slicer::Toolpath& t, const machines::MachineProfile& m) {
  const Produced out = produce(t, m, plan_options_from(t, 0.01), "x.gcode");
  const ParsedGcode parsed = parse_gcode(out.gcode);
  for (const auto& issue : parsed.issues) {
    // The parser reads LCD messages (M117 Open the valve) as words; only motion must be clean.
    EXPECT_NE(issue.what.find("M117"), std::string::npos) << "line " << issue.line << ": " << issue.what;
  }
  EXPECT_EQ(parsed.program.layers.size(), t.layers.size());
  if (!m.arcs) {
    EXPECT_TRUE(parsed.arc_lines.empty()) << "G2/G3 on a machine without arcs";
  }
  const bool e_words = out.gcode.find(" E") != std::string::npos;
  const double geometric = geometric_volume_mm3(t);
  if (m.deposition.model == DepositionModel::EVolumetric) {
    ASSERT_TRUE(m.deposition.relative_e) << "the volume check reads relative E";
    EXPECT_NEAR(deposit_e(out.gcode) * m.deposition.mm3_per_e, geometric, 0.005 * geometric);
    // The parsed deposit lengths x bead section give the same volume.
    double parsed_volume = 0.0;
    slicer::Vec3 at = parsed.program.start_mm;
    for (const auto& mv : parsed.program.moves) {
      if (mv.kind == slicer::MoveKind::Deposit) {
        const double h = parsed.program.layers.at(static_cast<std::size_t>(mv.layer)).height_mm;
        parsed_volume += move_length(at, mv) * slicer::bead_area_mm2(mv.width_mm, h);
      }
      if (mv.kind == slicer::MoveKind::Deposit || mv.kind == slicer::MoveKind::Travel) at = mv.end_mm;
    }
    EXPECT_NEAR(parsed_volume, geometric, 0.005 * geometric);
  } else {
    EXPECT_FALSE(e_words) << "E words on a " << machines::to_string(m.deposition.model) << " machine";
  }
  if (m.deposition.model == DepositionModel::Valve) expect_valve_brackets(out.gcode, m);
  // Report: both times, volume, fills.
  const auto& tot = out.report.at("totals");
  EXPECT_GE(tot.at("time_trapezoid_s").get<double>(), tot.at("time_naive_s").get<double>() * 0.999);
  EXPECT_NEAR(tot.at("ink_volume_mm3").get<double>(), geometric, 0.005 * geometric);
  EXPECT_NEAR(tot.at("syringe_fills").get<double>(),
              geometric / 1000.0 / m.deposition.reservoir_ml, 1e-3);
}

TEST(Produce, EveryGeneratorWithEveryDiwProfile) {
  int checked = 0;
  for (const auto& g : patterns::generators()) {
    const auto t = sample_toolpath(g);
    if (!t) continue;
    for (const auto& [name, description] : machines::list_profiles()) {
      const auto m = machines::load_profile(name);
      if (!is_diw(m)) continue;
      SCOPED_TRACE(g.name + " on " + name);
      check_one(*t, m);
      ++checked;
    }
  }
  EXPECT_GE(checked, 5);
}

TEST(Produce, HeaderCarriesBothTimesAndInk) {
  const auto t = sample_toolpath(*patterns::find_generator("scaffold"));
  const auto out = produce(*t, machines::load_profile("deltawasp-2040-clay"), plan_options_from(*t, 0.01), "x.gcode");
  for (const char* k : {"; estimate time_naive_s = ", "; estimate time_trapezoid_s = ",
                        "; estimate ink_volume_ml = ", "; estimate syringe_fills = ", "; layer 2: length "}) {
    EXPECT_NE(out.gcode.find(k), std::string::npos) << k;
  }
}

TEST(Produce, ViewerCopyHasRelativeEAndSaysNotForPrinting) {
  const auto t = sample_toolpath(*patterns::find_generator("scaffold"));
  const auto m = machines::load_profile("deltawasp-2040-clay-valve");
  const auto out = produce(*t, m, plan_options_from(*t, 0.01), "x.gcode", true);
  EXPECT_EQ(out.gcode.find(" E"), std::string::npos);
  EXPECT_NE(out.viewer_gcode.find("NOT FOR PRINTING"), std::string::npos);
  EXPECT_LT(out.viewer_gcode.find("G90"), out.viewer_gcode.find("M83"));
  EXPECT_NEAR(deposit_e(out.viewer_gcode), geometric_volume_mm3(*t), 0.005 * geometric_volume_mm3(*t));
}

}  // namespace
}  // namespace strand::post
