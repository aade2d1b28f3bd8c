#include "postprocess/preview/svg_layer.h"

#include <gtest/gtest.h>

#include "postprocess/inspect/check.h"

namespace strand::post {
namespace {

const char* kTwoLayers =
    ";LAYER:0\nG0 X0 Y0 Z0.5\n;FEATURE:node\nG1 X10 Y10\nG1 X10 Y0\nG1 X0 Y10\nG0 X20 "
    "Y20\n;FEATURE:ligament\nG1 X30 Y20\n"
    ";LAYER:1\nG0 X0 Y0 Z1\nG1 X77 Y0\n";

std::string svg_of(int layer) {
  const auto parsed = parse_gcode(kTwoLayers);
  const auto report = check_parsed(parsed, {});
  LayerMarks marks;
  for (const auto& l : report.layers) {
    if (l.layer == layer) marks = {l.crossings, l.touches};
  }
  return layer_svg(parsed.program, layer, marks, 0.01);
}

std::size_t count(const std::string& s, const std::string& what) {
  std::size_t n = 0;
  for (auto i = s.find(what); i != std::string::npos; i = s.find(what, i + 1)) ++n;
  return n;
}

TEST(SvgLayer, CrossingIsCircledInRedAtItsPointWithYUp) {
  const auto svg = svg_of(0);
  EXPECT_NE(svg.find("<circle cx=\"5.000\" cy=\"-5.000\""), std::string::npos) << svg;
  EXPECT_EQ(count(svg, "stroke=\"#e00000\""), 1u);
}

TEST(SvgLayer, FeaturesTravelsAndScaleBarAreDrawn) {
  const auto svg = svg_of(0);
  EXPECT_EQ(count(svg, "class=\"node\""), 1u);
  EXPECT_EQ(count(svg, "class=\"ligament\""), 1u);
  EXPECT_NE(svg.find("stroke-dasharray"), std::string::npos)
      << "travel from the node to the ligament";
  EXPECT_NE(svg.find(" mm</text>"), std::string::npos) << "scale bar";
  EXPECT_NE(svg.find(">node</text>"), std::string::npos) << "legend";
  EXPECT_EQ(svg.find(">infill</text>"), std::string::npos) << "legend lists only features drawn";
}

TEST(SvgLayer, OnlyTheChosenLayerIsDrawn) {
  EXPECT_EQ(svg_of(0).find("77.000"), std::string::npos);
  EXPECT_NE(svg_of(1).find("L77.000 0.000"), std::string::npos) << svg_of(1);
}

TEST(SvgLayer, ViewBoxCoversTheLayerInMillimetres) {
  const auto svg = svg_of(0);
  // Layer 0 spans x 0..30, y 0..20; 8 % margin of the larger side (30 mm) = 2.4 mm.
  EXPECT_NE(svg.find("viewBox=\"-2.400 -22.400 34.800 24.800\""), std::string::npos)
      << svg.substr(0, 200);
}

TEST(SvgLayer, SameInputGivesIdenticalBytes) { EXPECT_EQ(svg_of(0), svg_of(0)); }

}  // namespace
}  // namespace strand::post
