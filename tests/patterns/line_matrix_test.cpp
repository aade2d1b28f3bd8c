// The line-width matrix: its layout, the bead each flow asks for, the per-line speeds the
// planner gives, and the one-line refusals.
#include "patterns/line_matrix.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "machines/profile.h"
#include "patterns/registry.h"
#include "postprocess/plan/planner.h"
#include "slicer/input_error.h"

namespace strand::patterns {
namespace {

slicer::Toolpath matrix(const nlohmann::json& given) {
  return find_generator("line-matrix")->generate(slicer::resolve_params(line_matrix_table(), given));
}

std::string error_of(const nlohmann::json& given) {
  try {
    matrix(given);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(LineMatrix, OnlyTheNozzleIsRequiredAndEverySpeedMeetsEveryFlow) {
  const auto t = matrix({{"nozzle", 0.6}});
  const auto& lines = t.derived["lines"];
  ASSERT_EQ(lines.size(), 16u);
  std::set<std::pair<double, double>> pairs;
  for (const auto& l : lines) pairs.insert({l["speed_mm_min"].get<double>(), l["flow"].get<double>()});
  EXPECT_EQ(pairs.size(), 16u);
  ASSERT_EQ(t.layers.size(), 1u);
  // 16 lines then the 4 marks, closed squares outside the lines' box.
  ASSERT_EQ(t.layers[0].strokes.size(), 20u);
  ASSERT_EQ(t.derived["fiducials"].size(), 4u);
  double line_x = 0, line_y = 0;
  for (const auto& l : lines) {
    for (const char* end : {"start_mm", "end_mm"}) {
      line_x = std::max(line_x, std::abs(l[end][0].get<double>()));
      line_y = std::max(line_y, std::abs(l[end][1].get<double>()));
    }
  }
  for (const auto& f : t.derived["fiducials"]) {
    EXPECT_GT(std::abs(f["x_mm"].get<double>()) - f["size_mm"].get<double>() / 2, line_x + 0.6);
    EXPECT_GT(std::abs(f["y_mm"].get<double>()) - f["size_mm"].get<double>() / 2, line_y + 0.6);
  }
  for (std::size_t i = 16; i < 20; ++i) {
    const auto& s = t.layers[0].strokes[i];
    EXPECT_EQ(s.segments.size(), 4u);
    EXPECT_LT((s.end_mm() - s.start_mm).norm(), 1e-12) << "a mark closes on itself";
  }
}

TEST(LineMatrix, EachLinesBeadSectionIsItsFlowTimesTheNozzleBead) {
  const auto t = matrix({{"nozzle", 0.6}, {"flows", "0.5,1,2"}, {"speeds", "300"}});
  const double nominal = slicer::bead_area_mm2(0.6, 0.48);
  for (std::size_t i = 0; i < 3; ++i) {
    const auto& s = t.layers[0].strokes[i];
    const double flow = t.derived["lines"][i]["flow"];
    EXPECT_NEAR(slicer::bead_area_mm2(s.width_mm, s.height_mm), flow * nominal, 1e-9) << "flow " << flow;
    EXPECT_DOUBLE_EQ(t.derived["lines"][i]["width_mm"].get<double>(), s.width_mm);
  }
  EXPECT_NEAR(t.layers[0].strokes[1].width_mm, 0.6, 1e-12);
}

TEST(LineMatrix, ThePlannerPrintsEachLineAtItsOwnSpeed) {
  const auto t = matrix({{"nozzle", 0.6}, {"speeds", "150,600"}, {"flows", "1"}, {"speed", 250}});
  const auto m = machines::load_profile("deltawasp-2040-clay");
  const auto program = post::plan(t, m, post::plan_options_from(t, 0.01));
  std::vector<double> feeds;
  for (const auto& mv : program.moves) {
    if (mv.kind == slicer::MoveKind::Deposit && (feeds.empty() || feeds.back() != mv.feed_mm_per_min)) {
      feeds.push_back(mv.feed_mm_per_min);
    }
  }
  ASSERT_GE(feeds.size(), 3u);
  EXPECT_DOUBLE_EQ(feeds[0], 150.0);
  EXPECT_DOUBLE_EQ(feeds[1], 600.0);
  // The marks: the base speed times the profile's factor for frames.
  const auto frame = m.speed_factors.find(slicer::Feature::Frame);
  EXPECT_DOUBLE_EQ(feeds[2], 250.0 * (frame == m.speed_factors.end() ? 1.0 : frame->second));
}

// Raw text of a planned program, in order.
std::vector<std::string> texts_of(const slicer::MotionProgram& p) {
  std::vector<std::string> out;
  for (const auto& mv : p.moves) {
    if (mv.kind == slicer::MoveKind::Raw) out.push_back(slicer::raw_text(p, mv));
  }
  return out;
}

TEST(LineMatrix, RowsHoldOneFlowSoAPneumaticMachineChangesPressureOncePerRow) {
  const auto t = matrix({{"nozzle", 0.6}, {"speeds", "200,400,600"}, {"flows", "0.8,1.2"}});
  const auto& lines = t.derived["lines"];
  ASSERT_EQ(lines.size(), 6u);
  // Print order: the first row's three speeds, then the second row's (serpentine).
  for (std::size_t i = 0; i < 6; ++i) EXPECT_EQ(lines[i]["flow"].get<double>(), i < 3 ? 0.8 : 1.2) << i;
  EXPECT_EQ(lines[2]["speed_mm_min"], 600);
  EXPECT_EQ(lines[3]["speed_mm_min"], 600);

  const auto manual = machines::load_profile("deltawasp-2040-clay");
  const auto texts = texts_of(post::plan(t, manual, post::plan_options_from(t, 0.01)));
  std::vector<std::string> pauses, labels;
  for (const auto& x : texts) {
    if (x.starts_with("M117 Set flow")) pauses.push_back(x);
    if (x.starts_with("; line ")) labels.push_back(x);
  }
  // Two rows: the operator is asked twice (Marlin: message, then M0 waits), before each row.
  ASSERT_EQ(pauses.size(), 2u);
  EXPECT_EQ(pauses[0], "M117 Set flow 0.8, then resume\nM0 Set flow 0.8, then resume");
  EXPECT_NE(pauses[1].find("Set flow 1.2"), std::string::npos);
  ASSERT_EQ(labels.size(), 6u);
  EXPECT_EQ(labels[3], "; line 3: speed 600 mm/min, flow 1.2");

  // A pressure template: the value goes into it; no pause.
  auto regulated = machines::load_profile("deltawasp-2040-clay-valve");
  regulated.deposition.pressure_command = {"M42 P5 S{flow}"};
  const auto set = texts_of(post::plan(t, regulated, post::plan_options_from(t, 0.01)));
  EXPECT_EQ(std::count_if(set.begin(), set.end(), [](const std::string& x) { return x.starts_with("M42 P5 S1.2\n"); }), 1);
  EXPECT_EQ(std::count_if(set.begin(), set.end(), [](const std::string& x) { return x.find("M0") != std::string::npos; }), 0);

  // An E-driven machine takes the flow from the bead: no commands, E grows with the flow.
  const auto screw = machines::load_profile("deltawasp-2040-clay-ldm");
  const auto p = post::plan(t, screw, post::plan_options_from(t, 0.01));
  for (const auto& x : texts_of(p)) EXPECT_EQ(x.find("Set flow"), std::string::npos) << x;
}

TEST(LineMatrix, AnInksFlowScalesTheVolumeOnEDrivenMachinesAndIsSetOnceOnPneumaticOnes) {
  const auto t = find_generator("scaffold")->generate(
      slicer::resolve_params(find_generator("scaffold")->table(), {{"nozzle", 0.6}, {"gap", 1}, {"size", "10x10"}, {"layers", 2}}));
  auto volume = [](const slicer::MotionProgram& p) {
    double v = 0;
    for (const auto& mv : p.moves) v += mv.volume_mm3;
    return v;
  };
  const auto screw = machines::load_profile("deltawasp-2040-clay-ldm");
  auto o = post::plan_options_from(t, 0.01);
  const double plain = volume(post::plan(t, screw, o));
  o.flow = 1.25;
  EXPECT_NEAR(volume(post::plan(t, screw, o)), 1.25 * plain, 1e-9 * plain);
  const auto manual = machines::load_profile("deltawasp-2040-clay");
  const auto texts = texts_of(post::plan(t, manual, o));
  EXPECT_EQ(std::count_if(texts.begin(), texts.end(), [](const std::string& x) { return x.find("Set flow 1.25 for this ink") != std::string::npos; }), 1);
  EXPECT_NEAR(volume(post::plan(t, manual, o)), plain, 1e-9 * plain) << "pneumatic: the pressure sets the flow, not the volume";
}

TEST(LineMatrix, BadInputNamesTheParameterAndItsRange) {
  EXPECT_NE(error_of({{"nozzle", 0.6}, {"spacing", 1.5}}).find("line-matrix.spacing = 1.5: must be >= 2.4"),
            std::string::npos)
      << error_of({{"nozzle", 0.6}, {"spacing", 1.5}});
  EXPECT_NE(error_of({{"nozzle", 0.6}, {"fiducial-size", 1}}).find("line-matrix.fiducial-size = 1: must be >= 4 x nozzle = 2.4"),
            std::string::npos);
  EXPECT_NE(error_of({{"nozzle", 0.6}, {"layer-height", 0.1}}).find("line-matrix.layer-height = 0.1"), std::string::npos);
  EXPECT_NE(error_of({{"nozzle", 0.6}, {"speeds", "1,2,3,4,5,6,7,8,9,10,11"}, {"flows", "1,1.1,1.2,1.3,1.4,1.5,1.6,1.7,1.8,1.9"}})
                .find("line-matrix.speeds x flows = 110 lines: must be 1 to 100"),
            std::string::npos);
  EXPECT_NE(error_of(nlohmann::json::object()).find("line-matrix.nozzle: missing"), std::string::npos);
}

}  // namespace
}  // namespace strand::patterns
