// Tools by feature or by layer: the two written forms, the one-line refusals, strokes cut where
// their tool changes and grouped so a layer changes tool as few times as it can.
#include "postprocess/plan/tool_assignment.h"

#include <gtest/gtest.h>

#include "slicer/input_error.h"

namespace strand::post {
namespace {

using slicer::Feature;
using slicer::Vec2;

std::string error_of(const std::string& text) {
  try {
    tool_assignment_from_text(text, "tools");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ToolAssignment, FeaturesOrALayerCycleFromTheFlagOrAJobFile) {
  const auto a = tool_assignment_from_text("node=1,ligament=0,frame=0", "tools");
  EXPECT_EQ(a.by_feature.at(Feature::Node), 1);
  EXPECT_EQ(a.by_feature.at(Feature::Ligament), 0);
  EXPECT_EQ(a.highest(), 1);
  EXPECT_EQ(tool_assignment_from_text("layers=0,1,1", "tools").by_layer, (std::vector<int>{0, 1, 1}));
  const auto j = tool_assignment_from_json(nlohmann::json::parse(R"({"by_feature": {"node": 2}})"), "job.tools");
  EXPECT_EQ(j.by_feature.at(Feature::Node), 2);
  EXPECT_EQ(tool_assignment_from_json(nlohmann::json::parse(R"({"by_layer": [1, 0]})"), "job.tools").by_layer,
            (std::vector<int>{1, 0}));
  EXPECT_EQ(tool_assignment_from_json("layers=1", "job.tools").by_layer, (std::vector<int>{1}));
}

TEST(ToolAssignment, BadFormsAreOneLineNamingTheAllowedOnes) {
  EXPECT_NE(error_of("node").find("tools = node: must be FEATURE=TOOL"), std::string::npos) << error_of("node");
  EXPECT_NE(error_of("wing=1").find("wing is not a feature"), std::string::npos) << error_of("wing=1");
  EXPECT_NE(error_of("node=16").find("tool 16 must be a whole number 0 to 15"), std::string::npos);
  EXPECT_NE(error_of("node=1.5").find("must be a whole number"), std::string::npos);
  EXPECT_NE(error_of("layers=").find("must be a whole number"), std::string::npos);
  EXPECT_NE(error_of("node=1,node=0").find("node is given twice"), std::string::npos);
  EXPECT_NE(error_of("").find("must be"), std::string::npos);
  try {
    tool_assignment_from_json(nlohmann::json::parse(R"({"by_feature": {"node": 1}, "by_layer": [0]})"), "job.tools");
    ADD_FAILURE() << "both forms at once";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("job.tools: must be {\"by_feature\""), std::string::npos) << e.what();
  }
}

slicer::Stroke chiral_like() {
  // A ligament into a node pass, round it, and out along another ligament.
  slicer::Stroke s;
  s.start_mm = Vec2(0, 0);
  s.width_mm = 0.5;
  s.height_mm = 0.4;
  s.segments = {slicer::line_to(Vec2(5, 0), Feature::Ligament), slicer::arc_to(Vec2(7, 0), Vec2(6, 0), true, Feature::Node),
                slicer::arc_to(Vec2(5, 0), Vec2(6, 0), true, Feature::Node), slicer::line_to(Vec2(5, 5), Feature::Ligament)};
  return s;
}

TEST(ToolAssignment, AStrokeIsCutWhereItsToolChangesAndTheLayerGroupedByTool) {
  const auto a = tool_assignment_from_text("node=1", "tools");
  slicer::Stroke other;
  other.start_mm = Vec2(20, 0);
  other.segments = {slicer::line_to(Vec2(30, 0), Feature::Ligament)};
  const auto out = assign_tools({chiral_like(), other}, a, 0, 0);
  // The held tool first: both ligament pieces of the first stroke and the other stroke, then
  // the node pass, its two arcs together.
  ASSERT_EQ(out.size(), 4u);
  EXPECT_EQ(out[0].tool, 0);
  EXPECT_EQ(out[0].segments.size(), 1u);
  EXPECT_EQ(out[1].start_mm, Vec2(5, 0)) << "the second ligament starts where the node pass ended";
  EXPECT_EQ(out[1].tool, 0);
  EXPECT_EQ(out[2].start_mm, Vec2(20, 0));
  EXPECT_EQ(out[3].tool, 1);
  EXPECT_EQ(out[3].start_mm, Vec2(5, 0));
  EXPECT_EQ(out[3].segments.size(), 2u);
  EXPECT_EQ(out[3].end_mm(), Vec2(5, 0));
  // Holding tool 1 already, the node pass goes first.
  EXPECT_EQ(assign_tools({chiral_like(), other}, a, 3, 1).front().tool, 1);
  // Every segment kept once.
  std::size_t segments = 0;
  for (const auto& s : out) segments += s.segments.size();
  EXPECT_EQ(segments, 5u);
}

TEST(ToolAssignment, ALayerCycleSetsEveryStrokeOfTheLayer) {
  const auto a = tool_assignment_from_text("layers=0,1,1", "tools");
  for (int layer = 0; layer < 6; ++layer) {
    for (const auto& s : assign_tools({chiral_like()}, a, layer, 0)) EXPECT_EQ(s.tool, layer % 3 == 0 ? 0 : 1) << layer;
    EXPECT_EQ(assign_tools({chiral_like()}, a, layer, 0).size(), 1u) << "not cut";
  }
}

}  // namespace
}  // namespace strand::post
