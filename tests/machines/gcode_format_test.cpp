#include "machines/gcode_format.h"

#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <limits>
#include <random>

namespace strand::machines {
namespace {

// The reference: round to the decimals, then std::to_chars of that double.
std::string reference(double v, int decimals) {
  const double scale = std::pow(10.0, decimals);
  double r = std::round(v * scale) / scale;
  if (r == 0.0) r = 0.0;
  char buf[400];
  auto res = std::to_chars(buf, buf + sizeof buf, r, std::chars_format::fixed, decimals);
  return std::string(buf, res.ptr);
}

TEST(GcodeFormat, KnownValues) {
  EXPECT_EQ(fmt_xyz(1.0005), "1.001");
  EXPECT_EQ(fmt_xyz(-0.0004), "0.000");
  EXPECT_EQ(fmt_xyz(-12.3456), "-12.346");
  EXPECT_EQ(fmt_e(0.000004), "0.00000");
  EXPECT_EQ(fmt_feed(249.5), "250");
  EXPECT_EQ(fmt_feed(-0.4), "0");
}

TEST(GcodeFormat, IntegerWriterMatchesToCharsOnRandomAndEdgeValues) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> small(-1000.0, 1000.0), wide(-1e13, 1e13);
  for (int decimals : {0, 1, 3, 4, 5}) {
    for (int i = 0; i < 100000; ++i) {
      const double v = i % 3 == 0 ? wide(rng) : small(rng);
      ASSERT_EQ(fmt_fixed(v, decimals), reference(v, decimals)) << v << " " << decimals;
      const double half = (std::round(v * 1000) + 0.5) / 1000;  // ties at the last digit
      ASSERT_EQ(fmt_fixed(half, decimals), reference(half, decimals)) << half;
    }
  }
  for (double v : {0.0, -0.0, 1e15, -1e15, 4.6e15, 1e300, -1e300,
                   std::numeric_limits<double>::infinity(), std::nan("")}) {
    EXPECT_EQ(fmt_fixed(v, 3), reference(v, 3)) << v;
  }
}

}  // namespace
}  // namespace strand::machines
