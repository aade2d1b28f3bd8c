#include "slicer/substrate_params.h"

#include <gtest/gtest.h>

#include "slicer/input_error.h"

namespace strand::slicer {
namespace {

std::string error_of(const nlohmann::json& given) {
  try {
    substrate_from(given);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(SubstrateParams, NothingGivenIsAFlatJob) {
  EXPECT_FALSE(substrate_from(nlohmann::json::object()).has_value());
  EXPECT_FALSE(substrate_from(nullptr).has_value());
}

TEST(SubstrateParams, CylinderDefaultsToPatchMeasuredAtTheSurface) {
  const auto s = substrate_from({{"type", "cylinder"}, {"radius", 20}, {"length", 80}});
  ASSERT_TRUE(s.has_value());
  EXPECT_EQ(s->wrap, Wrap::Patch);
  EXPECT_EQ(s->arc_length_at, ArcLengthAt::Surface);
  EXPECT_DOUBLE_EQ(s->radius_mm, 20.0);
}

TEST(SubstrateParams, RadiusMustBePositive) {
  EXPECT_NE(error_of({{"type", "cylinder"}, {"radius", 0}, {"length", 80}})
                .find("substrate.radius = 0: must be in (0, 10000] (mm)"),
            std::string::npos);
  EXPECT_NE(error_of({{"type", "cylinder"}, {"radius", -3}, {"length", 80}})
                .find("substrate.radius = -3"),
            std::string::npos);
}

TEST(SubstrateParams, ProblemsAreNamedTogether) {
  const std::string e = error_of({{"radius", 20}, {"wrap", "spiral"}});
  EXPECT_NE(e.find("substrate.wrap = spiral: must be one of patch, full"), std::string::npos) << e;
  EXPECT_EQ(error_of({{"radius", 20}}).find("substrate.type: missing"), 0u);
  EXPECT_NE(error_of({{"type", "cylinder"}}).find("substrate.radius: missing"), std::string::npos);
  EXPECT_NE(error_of({{"type", "cone"}, {"radius", 1}, {"length", 1}})
                .find("substrate.type = cone: must be one of cylinder"),
            std::string::npos);
}

TEST(SubstrateParams, FlagsFollowTheTableKeys) {
  EXPECT_EQ(substrate_flag("type"), "substrate");
  EXPECT_EQ(substrate_flag("radius"), "substrate-radius");
  EXPECT_EQ(substrate_flag("length"), "substrate-length");
  EXPECT_EQ(substrate_flag("wrap"), "wrap");
  EXPECT_EQ(substrate_flag("arc-length-at"), "arc-length-at");
}

TEST(SubstrateParams, FullWrapMeasuredAtDepositionKeepsTheFirstLayersAngles) {
  SubstrateSpec s{"cylinder", 20, 80, Wrap::Full, ArcLengthAt::Deposition};
  const CylinderSpec c = cylinder_spec(s, 0.8);
  EXPECT_DOUBLE_EQ(c.bead_inset_mm, 0.4);
  EXPECT_DOUBLE_EQ(c.fixed_measure_offset_mm, 0.8);
  s.wrap = Wrap::Patch;
  EXPECT_DOUBLE_EQ(cylinder_spec(s, 0.8).fixed_measure_offset_mm, 0.0);
}

}  // namespace
}  // namespace strand::slicer
