#include "postprocess/inspect/ngc_expression.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

namespace strand::post {
namespace {

// #1 = 3, #2 = -4, #<width> = 0.4, #<_z> = 1.2 (as a reader's current position).
class TableScope : public NgcScope {
 public:
  double numbered(int i) const override {
    if (i == 5400) throw NgcUnsupported("system parameter #5400");
    const auto it = numbered_.find(i);
    return it == numbered_.end() ? 0.0 : it->second;
  }
  std::optional<double> named(const std::string& n) const override {
    const auto it = named_.find(n);
    if (it == named_.end()) return std::nullopt;
    return it->second;
  }

 private:
  std::map<int, double> numbered_{{1, 3.0}, {2, -4.0}, {3, 1.0}};
  std::map<std::string, double> named_{{"width", 0.4}, {"_z", 1.2}};
};

struct Row {
  const char* text;
  double value;
};

// Values worked out by hand from the RS274NGC rules (degrees, precedence, MOD sign).
const Row kTable[] = {
    {"1.5", 1.5},
    {"-2", -2.0},
    {".5", 0.5},
    {"[1 + 2 * 3]", 7.0},  // * before +
    {"[[1 + 2] * 3]", 9.0},
    {"[10 - 4 - 3]", 3.0},    // left to right
    {"[2 ** 3 ** 2]", 64.0},  // left to right: (2^3)^2
    {"[2 POWER 10]", 1024.0},
    {"[2 * 3 ** 2]", 18.0},  // power first
    {"[7 MOD 3]", 1.0},
    {"[-7 MOD 3]", 2.0},  // LinuxCNC: the result takes the divisor's sign
    {"[7.5 / 2.5]", 3.0},
    {"ABS[-2.5]", 2.5},
    {"SQRT[16]", 4.0},
    {"SIN[30]", 0.5},  // degrees
    {"COS[60]", 0.5},
    {"TAN[45]", 1.0},
    {"ATAN[1]/[1]", 45.0},
    {"ATAN[1]/[-1]", 135.0},  // the quadrant from both signs
    {"ASIN[1]", 90.0},
    {"ACOS[0]", 90.0},
    {"ROUND[2.5]", 3.0},
    {"ROUND[-2.5]", -3.0},  // half away from zero
    {"FIX[-2.5]", -3.0},    // down
    {"FUP[-2.5]", -2.0},    // up
    {"FIX[2.7]", 2.0},
    {"EXP[0]", 1.0},
    {"LN[1]", 0.0},
    {"[1 EQ 1.00001]", 1.0},  // within LinuxCNC's 1e-4
    {"[1 NE 2]", 1.0},
    {"[2 GT 1]", 1.0},
    {"[1 GE 1]", 1.0},
    {"[2 LT 1]", 0.0},
    {"[1 LE 0.5]", 0.0},
    {"[1 AND 0]", 0.0},
    {"[1 OR 0]", 1.0},
    {"[1 XOR 1]", 0.0},
    {"[1 + 1 EQ 2]", 1.0},         // + before EQ
    {"[1 LT 2 AND 3 GT 2]", 1.0},  // comparisons before AND
    {"#1", 3.0},
    {"#[1 + 1]", -4.0},  // computed index
    {"##3", 3.0},        // #3 = 1, so ##3 = #1
    {"#9", 0.0},         // unset numbered parameters read 0
    {"#<width>", 0.4},
    {"#<W i D t h>", 0.4},  // names ignore case and spaces
    {"[#<_z> +0.2]", 1.4},  // Vitaprint's layer change
    {"[#1 * #<width>]", 1.2},
    {"-[#2]", 4.0},
    {"[ 1 + [ 2 * [ 3 + 1 ] ] ]", 9.0},
    {"[sin[90]*2]", 2.0},  // functions in lower case
    {"EXISTS[#<width>]", 1.0},
    {"EXISTS[#<height>]", 0.0},
};

TEST(NgcExpression, EvaluatesTheTable) {
  const TableScope scope;
  for (const Row& row : kTable) {
    EXPECT_NEAR(ngc_evaluate(row.text, scope), row.value, 1e-9) << row.text;
  }
}

TEST(NgcExpression, ErrorsSayWhy) {
  const TableScope scope;
  const std::pair<const char*, const char*> kErrors[] = {
      {"[1 / 0]", "division by zero"},
      {"[5 MOD 0]", "division by zero"},
      {"[1 / [#2 + 4]]", "division by zero"},
      {"[0 ** -1]", "division by zero"},
      {"SQRT[-1]", "sqrt[-1]"},
      {"LN[0]", "ln[0]"},
      {"ASIN[2]", "outside [-1, 1]"},
      {"[-8 ** 0.5]", "fractional power"},
      {"EXP[1000]", "not a finite number"},
      {"#<height>", "#<height> is used before it is set"},
      {"[1 + 2", "']' expected"},
      {"[1 + ]", "a number expected"},
      {"FOO[1]", "unknown function"},
      {"#0", "must be a whole number in [1, 5602]"},
      {"#1.5", "must be a whole number"},
      {"1e5", "malformed number"},
      {"[1] 2", "unexpected"},
  };
  for (const auto& [text, why] : kErrors) {
    try {
      ngc_evaluate(text, scope);
      ADD_FAILURE() << text << " evaluated";
    } catch (const NgcError& e) {
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << text << ": " << e.what();
    }
  }
  EXPECT_THROW(ngc_evaluate("#5400", scope), NgcUnsupported);
  EXPECT_THROW(ngc_evaluate("#<_hal_pin>", scope), NgcUnsupported);
}

TEST(NgcExpression, NestingIsBounded) {
  const TableScope scope;
  std::string deep;
  for (int i = 0; i < 10000; ++i) deep += '[';
  EXPECT_THROW(ngc_evaluate(deep, scope), NgcError);
  std::string signs(10000, '-');
  EXPECT_THROW(ngc_evaluate(signs + "1", scope), NgcError);
  std::string hashes(10000, '#');
  EXPECT_THROW(ngc_evaluate(hashes + "1", scope), NgcError);
  std::string within = "1";
  for (int i = 0; i < 20; ++i) within = "[" + within + " + 1]";
  EXPECT_EQ(ngc_evaluate(within, scope), 21.0);
}

}  // namespace
}  // namespace strand::post
