#include "slicer/params.h"

#include <gtest/gtest.h>

#include "slicer/input_error.h"

namespace strand::slicer {
namespace {

const ParamTable& table() {
  static const ParamTable t = {
      "demo",
      {
          {"nozzle", ParamType::Number, "mm", "d", 0.0, true, 10.0},
          {"layers", ParamType::Integer, "", "n", 1.0, false, 100.0, false, 3},
          {"angles", ParamType::NumberList, "deg", "a", -360.0, false, 360.0, false, "0,90"},
          {"size", ParamType::Size2, "mm", "s", 0.0, true, 1000.0},
      }};
  return t;
}

TEST(ResolveParams, FillsDefaultsAndNormalisesText) {
  const auto v = resolve_params(table(), {{"nozzle", 0.5}, {"size", "36x20"}});
  EXPECT_EQ(v.at("layers"), 3);
  EXPECT_EQ(v.at("angles"), nlohmann::json({0.0, 90.0}));
  EXPECT_EQ(v.at("size"), nlohmann::json({36.0, 20.0}));
}

TEST(ResolveParams, ReportsEveryProblemInOneMessage) {
  try {
    resolve_params(table(), {{"nozzle", 0}, {"layers", 0}, {"colour", "red"}});
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("demo.nozzle = 0: must be in (0, 10] (mm)"), std::string::npos) << m;
    EXPECT_NE(m.find("demo.layers = 0: must be in [1, 100]"), std::string::npos) << m;
    EXPECT_NE(m.find("demo.colour: unknown parameter"), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << "one line";
  }
}

TEST(ParseParamText, RejectsTextThatIsNotANumber) {
  EXPECT_THROW(parse_param_text(table(), table().defs[0], "abc"), InputError);
  EXPECT_THROW(parse_param_text(table(), table().defs[3], "36x"), InputError);
  EXPECT_EQ(parse_param_text(table(), table().defs[0], "0.84"), 0.84);
}

TEST(ResolveParams, IntegerRejectsFraction) {
  EXPECT_THROW(resolve_params(table(), {{"nozzle", 1}, {"layers", 2.5}}), InputError);
}

}  // namespace
}  // namespace strand::slicer
