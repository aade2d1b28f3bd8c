// Filament collapse test: the table, the checked parameters, the pillars and the filament.
#include "patterns/collapse_test.h"

#include <algorithm>
#include <cmath>

#include "patterns/ink_test_marks.h"
#include "slicer/input_error.h"

namespace strand::patterns {

using slicer::ParamType;
using slicer::Vec2;

namespace {

constexpr std::size_t kMaxGaps = 20;

// A solid square of side `side` with lower-left corner `corner`: nozzle-wide lines a nozzle
// apart (spread evenly) along y (`along_y`) or x, joined into one serpentine.
slicer::Stroke pillar_layer(const Vec2& corner, double side, bool along_y, double d, double h) {
  const int lines = std::max(2, static_cast<int>(std::lround((side - d) / d)) + 1);
  const double pitch = (side - d) / (lines - 1);
  auto point = [&](double across, double along) -> Vec2 {
    return along_y ? corner + Vec2(across, along) : corner + Vec2(along, across);
  };
  slicer::Stroke s;
  s.start_mm = point(d / 2, d / 2);
  for (int k = 0; k < lines; ++k) {
    const double a = d / 2 + k * pitch;
    const double from = k % 2 == 0 ? d / 2 : side - d / 2, to = side - from;
    if (k > 0) s.segments.push_back(slicer::line_to(point(a, from), slicer::Feature::Infill));
    s.segments.push_back(slicer::line_to(point(a, to), slicer::Feature::Infill));
  }
  s.width_mm = d;
  s.height_mm = h;
  return s;
}

}  // namespace

const slicer::ParamTable& collapse_test_table() {
  static const slicer::ParamTable kTable = {
      "collapse-test",
      {
          {"nozzle", ParamType::Number, "mm", "nozzle diameter; required", 0.0, true, 10.0},
          {"gaps", ParamType::NumberList, "mm", "gaps between neighbouring pillars, one span each", 0.0, true, 100.0, false, "1,2,4,8,16"},
          {"pillar-size", ParamType::Number, "mm", "side of each square pillar; at least 3 x nozzle", 0.0, true, 100.0, false, nullptr, "max(3, 5 * nozzle)"},
          {"fiducial-size", ParamType::Number, "mm", "side of the square marks at the corners; at least 4 x nozzle", 0.0, true, 100.0, false, nullptr, "max(3, 5 * nozzle)"},
          {"layer-height", ParamType::Number, "mm", "layer height h, allowed 0.5*nozzle to 1.0*nozzle", 0.0, true, 10.0, false, nullptr, "0.8 * nozzle"},
          {"speed", ParamType::Number, "mm/min", "print speed", 0.0, true, 100000.0, false, 250.0},
          {"layers", ParamType::Integer, "", "layers: the pillars, then the filament as the last", 2.0, false, 500.0, false, 6},
      }};
  return kTable;
}

CollapseTestParams collapse_test_params_from(const nlohmann::json& v) {
  if (!v.contains("nozzle")) throw InputError("collapse-test.nozzle: missing (required, > 0 mm)");
  std::vector<std::string> problems;
  CollapseTestParams p;
  p.nozzle_mm = v.at("nozzle").get<double>();
  const double d = p.nozzle_mm;
  p.gaps_mm = v.at("gaps").get<std::vector<double>>();
  p.pillar_mm = v.contains("pillar-size") ? v.at("pillar-size").get<double>() : std::max(3.0, 5 * d);
  p.fiducial_mm = v.contains("fiducial-size") ? v.at("fiducial-size").get<double>() : std::max(3.0, 5 * d);
  p.layer_height_mm = v.contains("layer-height") ? v.at("layer-height").get<double>() : 0.8 * d;
  p.speed_mm_per_min = v.at("speed").get<double>();
  p.layers = v.at("layers").get<int>();
  if (p.gaps_mm.empty() || p.gaps_mm.size() > kMaxGaps) {
    problems.push_back("collapse-test.gaps: " + std::to_string(p.gaps_mm.size()) + " gaps: must be 1 to " +
                       std::to_string(kMaxGaps));
  }
  if (p.pillar_mm < 3 * d - 1e-9) {
    problems.push_back(slicer::problem("collapse-test", "pillar-size", p.pillar_mm,
                                       "must be >= 3 x nozzle = " + slicer::short_number(std::round(3e6 * d) / 1e6), "mm"));
  }
  check_layer_and_marks("collapse-test", d, p.layer_height_mm, p.fiducial_mm, problems);
  if (!problems.empty()) throw InputError(problems);
  return p;
}

std::unique_ptr<slicer::LayerSource> collapse_test_layers(const CollapseTestParams& p) {
  const double d = p.nozzle_mm, h = p.layer_height_mm, side = p.pillar_mm;
  std::vector<double> left = {0.0};  // pillars' left faces
  for (double g : p.gaps_mm) left.push_back(left.back() + side + g);
  const double half_x = (left.back() + side) / 2;
  for (double& v : left) v -= half_x;

  nlohmann::json gaps = nlohmann::json::array();
  for (std::size_t k = 0; k < p.gaps_mm.size(); ++k) {
    gaps.push_back({{"index", k},
                    {"gap_mm", p.gaps_mm[k]},
                    {"start_mm", {left[k] + side, 0.0}},
                    {"end_mm", {left[k + 1], 0.0}}});
  }
  const double mx = half_x + 5 * d + p.fiducial_mm / 2, my = side / 2 + 5 * d + p.fiducial_mm / 2;
  slicer::Toolpath t;
  t.generator = "collapse-test";
  nlohmann::json fiducials;
  for (int k = 0; k + 1 < p.layers; ++k) {
    slicer::Layer layer{(k + 1) * h, h, {}};
    for (double x : left) layer.strokes.push_back(pillar_layer(Vec2(x, -side / 2), side, k % 2 == 0, d, h));
    if (k == 0) fiducials = add_corner_marks(layer, mx, my, p.fiducial_mm, d, h);
    t.layers.push_back(std::move(layer));
  }
  slicer::Layer top{p.layers * h, h, {}};
  top.strokes.push_back(straight_bead(Vec2(-half_x + d / 2, 0.0), Vec2(half_x - d / 2, 0.0), d, h));
  t.layers.push_back(std::move(top));
  t.derived = {{"test", "collapse"},
               {"nozzle_mm", d},
               {"layer_height_mm", h},
               {"footprint_mm", {2 * mx + p.fiducial_mm, 2 * my + p.fiducial_mm}},
               {"height_mm", p.layers * h},
               {"pillar_mm", side},
               {"pillar_height_mm", (p.layers - 1) * h},
               {"filament_z_mm", p.layers * h},
               {"gaps", gaps},
               {"fiducials", fiducials}};
  return std::make_unique<slicer::ToolpathLayers>(std::move(t));
}

}  // namespace strand::patterns
