// Sweep constraints: grammar, names with dashes, slack for range rounding, bad syntax.
#include "jobs/sweep_constraint.h"

#include <gtest/gtest.h>

#include "slicer/input_error.h"

namespace strand::jobs {
namespace {

TEST(SweepConstraint, ComparesParametersAndArithmetic) {
  const auto c = parse_constraint("pitch - nozzle >= 0.5 * (nozzle + 0)", "w");
  EXPECT_EQ(c.names, (std::vector<std::string>{"nozzle", "pitch"}));
  EXPECT_TRUE(holds(c, {{"pitch", 2.0}, {"nozzle", 1.0}}));
  EXPECT_FALSE(holds(c, {{"pitch", 1.4}, {"nozzle", 1.0}}));
}

TEST(SweepConstraint, DashInsideANameIsPartOfTheName) {
  const auto c = parse_constraint("layer-height <= nozzle", "w");
  EXPECT_EQ(c.names, (std::vector<std::string>{"layer-height", "nozzle"}));
  EXPECT_TRUE(holds(c, {{"layer-height", 0.5}, {"nozzle", 0.6}}));
}

TEST(SweepConstraint, RangeRoundingDoesNotFlipEquality) {
  const double from_range = 0.8 + 2 * 0.4;  // 1.6000000000000001
  EXPECT_TRUE(holds(parse_constraint("gap <= 1.6", "w"), {{"gap", from_range}}));
  EXPECT_TRUE(holds(parse_constraint("gap == 1.6", "w"), {{"gap", from_range}}));
  EXPECT_FALSE(holds(parse_constraint("gap > 1.6", "w"), {{"gap", from_range}}));
}

TEST(SweepConstraint, UnaryMinusAndPrecedence) {
  EXPECT_TRUE(holds(parse_constraint("-a + 2 * 3 == 5", "w"), {{"a", 1.0}}));
  EXPECT_TRUE(holds(parse_constraint("(a + 2) * 3 == 9", "w"), {{"a", 1.0}}));
}

TEST(SweepConstraint, SyntaxErrorsNameTheKeyPath) {
  for (const char* bad : {"gap", "gap >=", "gap >= nozzle)", "gap = nozzle", "system(1) > 0", "gap >= 1 2"}) {
    try {
      parse_constraint(bad, "sweep.where[3]");
      ADD_FAILURE() << bad << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("sweep.where[3]"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace strand::jobs
