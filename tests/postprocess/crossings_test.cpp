#include "postprocess/crossings.h"

#include <gtest/gtest.h>

#include "postprocess/gcode_parser.h"

namespace strand::post {
namespace {

ContactReport contacts(const char* gcode) {
  return find_contacts(parse_gcode(gcode).program, 0.01, 1e-3);
}

TEST(Crossings, SelfCrossingInOneStrandIsFoundWithItsPoint) {
  const auto r = contacts("G0 X0 Y0 Z0.5\nG1 X10 Y10\nG1 X10 Y0\nG1 X0 Y10\n");
  ASSERT_EQ(r.crossings.size(), 1u);
  EXPECT_NEAR(r.crossings[0].at_mm.x(), 5.0, 1e-9);
  EXPECT_NEAR(r.crossings[0].at_mm.y(), 5.0, 1e-9);
}

TEST(Crossings, SerpentineHasNoContacts) {
  const auto r = contacts("G0 X0 Y0 Z0.5\nG1 X10\nG1 Y1\nG1 X0\nG1 Y2\nG1 X10\n");
  EXPECT_TRUE(r.crossings.empty());
  EXPECT_TRUE(r.touches.empty());
}

TEST(Crossings, DifferentLayersNeverCross) {
  const auto r = contacts(";LAYER:0\nG0 X0 Y5 Z0.5\nG1 X10 Y5\n;LAYER:1\nG0 X5 Y0 Z1\nG1 X5 Y10\n");
  EXPECT_TRUE(r.crossings.empty());
}

TEST(Crossings, EndingOnAFilamentIsATouch) {
  const auto r = contacts("G0 X0 Y0 Z0.5\nG1 X10\nG0 X5 Y5\nG1 X5 Y0\n");
  EXPECT_TRUE(r.crossings.empty());
  ASSERT_EQ(r.touches.size(), 1u);
  EXPECT_NEAR(r.touches[0].at_mm.x(), 5.0, 1e-9);
}

TEST(Crossings, ArcCrossingALineIsFound) {
  const auto r = contacts("G0 X-2 Y0 Z0.5\nG1 X2 Y0\nG0 X1 Y-1\nG3 X1 Y1 I-1 J1\n");
  EXPECT_EQ(r.crossings.size(), 1u);
}

}  // namespace
}  // namespace strand::post
