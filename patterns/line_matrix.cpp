// Line-width matrix: the table, the checked parameters and the layout. Lines run along x;
// columns hold one speed each, rows one flow each, printed row by row as a serpentine of
// separate strokes (a travel between lines: each line's speed and bead differ), then the
// square marks
// (patterns/ink_test_marks.h).
#include "patterns/line_matrix.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "patterns/ink_test_marks.h"
#include "slicer/input_error.h"

namespace strand::patterns {

using slicer::ParamType;
using slicer::Vec2;

namespace {

constexpr std::size_t kMaxLines = 100;

}  // namespace

double width_for_flow(double nozzle_mm, double layer_height_mm, double flow) {
  const double h = layer_height_mm;
  const double area = flow * slicer::bead_area_mm2(nozzle_mm, h);
  const double round_part = std::numbers::pi * h * h / 4;
  // Inverse of bead_area_mm2: a stadium while the bead is at least as wide as high.
  if (area >= round_part) return h + (area - round_part) / h;
  return 4 * area / (std::numbers::pi * h);
}

const slicer::ParamTable& line_matrix_table() {
  static const slicer::ParamTable kTable = {
      "line-matrix",
      {
          {"nozzle", ParamType::Number, "mm", "nozzle diameter; required", 0.0, true, 10.0},
          {"speeds", ParamType::NumberList, "mm/min", "one column of lines per speed", 1.0, false, 100000.0, false, "200,300,450,600"},
          {"flows", ParamType::NumberList, "", "one row per flow: bead section relative to a nozzle-wide bead (E multiplier)", 0.2, false, 5.0, false, "0.8,1,1.25,1.5"},
          {"length", ParamType::Number, "mm", "length of each line", 2.0, false, 200.0, false, 20.0},
          {"spacing", ParamType::Number, "mm", "centre-to-centre distance between rows, and between columns' ends; at least 4 x nozzle", 0.0, true, 100.0, false, nullptr, "5 * nozzle"},
          {"fiducial-size", ParamType::Number, "mm", "side of the square marks at the corners; at least 4 x nozzle", 0.0, true, 100.0, false, nullptr, "max(3, 5 * nozzle)"},
          {"layer-height", ParamType::Number, "mm", "layer height h, allowed 0.5*nozzle to 1.0*nozzle", 0.0, true, 10.0, false, nullptr, "0.8 * nozzle"},
          {"speed", ParamType::Number, "mm/min", "speed of the fiducial marks", 0.0, true, 100000.0, false, 250.0},
          {"layers", ParamType::Integer, "", "layers of the same lines (1 for the width matrix; more to measure height)", 1.0, false, 50.0, false, 1},
      }};
  return kTable;
}

LineMatrixParams line_matrix_params_from(const nlohmann::json& v) {
  if (!v.contains("nozzle")) throw InputError("line-matrix.nozzle: missing (required, > 0 mm)");
  std::vector<std::string> problems;
  LineMatrixParams p;
  p.nozzle_mm = v.at("nozzle").get<double>();
  const double d = p.nozzle_mm;
  p.speeds_mm_per_min = v.at("speeds").get<std::vector<double>>();
  p.flows = v.at("flows").get<std::vector<double>>();
  p.length_mm = v.at("length").get<double>();
  p.spacing_mm = v.contains("spacing") ? v.at("spacing").get<double>() : 5 * d;
  p.fiducial_mm = v.contains("fiducial-size") ? v.at("fiducial-size").get<double>() : std::max(3.0, 5 * d);
  p.layer_height_mm = v.contains("layer-height") ? v.at("layer-height").get<double>() : 0.8 * d;
  p.speed_mm_per_min = v.at("speed").get<double>();
  p.layers = v.at("layers").get<int>();
  const auto n = p.speeds_mm_per_min.size() * p.flows.size();
  if (p.speeds_mm_per_min.empty() || p.flows.empty() || n > kMaxLines) {
    problems.push_back("line-matrix.speeds x flows = " + std::to_string(n) +
                       " lines: must be 1 to " + std::to_string(kMaxLines));
  }
  if (p.layer_height_mm < 0.5 * d - 1e-12 || p.layer_height_mm > d + 1e-12) {
    problems.push_back(slicer::problem("line-matrix", "layer-height", p.layer_height_mm,
                                       "must be in [0.5, 1] x nozzle = [" + slicer::short_number(0.5 * d) +
                                           ", " + slicer::short_number(d) + "]", "mm"));
  }
  if (problems.empty()) {
    const double widest = width_for_flow(d, p.layer_height_mm, *std::max_element(p.flows.begin(), p.flows.end()));
    const double least = std::max(4 * d, 2.5 * widest);
    if (p.spacing_mm < least - 1e-9) {
      problems.push_back(slicer::problem("line-matrix", "spacing", p.spacing_mm,
                                         "must be >= " + slicer::short_number(least) +
                                             " (4 x nozzle and 2.5 x the widest bead, so lines stay apart in a photo)", "mm"));
    }
  }
  if (p.fiducial_mm < 4 * d - 1e-9) {
    problems.push_back(slicer::problem("line-matrix", "fiducial-size", p.fiducial_mm,
                                       "must be >= 4 x nozzle = " + slicer::short_number(4 * d), "mm"));
  }
  if (!problems.empty()) throw InputError(problems);
  return p;
}

std::unique_ptr<slicer::LayerSource> line_matrix_layers(const LineMatrixParams& p) {
  const std::size_t columns = p.speeds_mm_per_min.size(), rows = p.flows.size();
  const double pitch_x = p.length_mm + p.spacing_mm;
  const double x0 = -((columns - 1) * pitch_x + p.length_mm) / 2;
  const double y0 = -((rows - 1) * p.spacing_mm) / 2;
  const double h = p.layer_height_mm;

  slicer::Layer layer{h, h, {}};
  nlohmann::json lines = nlohmann::json::array();
  std::vector<double> speeds, flows;
  std::vector<std::string> labels;
  // Row by row (one flow each, so a pneumatic machine changes its pressure once per row),
  // columns alternately rightward and leftward, each line from the end nearest the last.
  for (std::size_t r = 0; r < rows; ++r) {
    const bool leftward = r % 2 == 1;
    for (std::size_t k = 0; k < columns; ++k) {
      const std::size_t c = leftward ? columns - 1 - k : k;
      const double y = y0 + r * p.spacing_mm;
      Vec2 a(x0 + c * pitch_x, y), b(a.x() + p.length_mm, y);
      if (leftward) std::swap(a, b);
      const double w = width_for_flow(p.nozzle_mm, h, p.flows[r]);
      layer.strokes.push_back(straight_bead(a, b, w, h));
      speeds.push_back(p.speeds_mm_per_min[c]);
      flows.push_back(p.flows[r]);
      labels.push_back("line " + std::to_string(lines.size()) + ": speed " + slicer::short_number(p.speeds_mm_per_min[c]) +
                       " mm/min, flow " + slicer::short_number(p.flows[r]));
      lines.push_back({{"index", lines.size()},
                       {"speed_mm_min", p.speeds_mm_per_min[c]},
                       {"flow", p.flows[r]},
                       {"start_mm", {a.x(), a.y()}},
                       {"end_mm", {b.x(), b.y()}},
                       {"width_mm", w}});
    }
  }
  // Marks outside the lines' box, one spacing plus half a mark beyond it, at the last row's
  // flow (no change of pressure for them).
  const double mx = -x0 + p.spacing_mm + p.fiducial_mm / 2;
  const double my = -y0 + p.spacing_mm + p.fiducial_mm / 2;
  const nlohmann::json fiducials = add_corner_marks(layer, mx, my, p.fiducial_mm, p.nozzle_mm, h);
  for (std::size_t k = 0; k < fiducials.size(); ++k) {
    speeds.push_back(p.speed_mm_per_min);
    flows.push_back(p.flows.back());
    labels.push_back("fiducial mark " + std::to_string(k));
  }

  slicer::Toolpath t;
  t.generator = "line-matrix";
  nlohmann::json all_speeds = nlohmann::json::array(), all_flows = nlohmann::json::array(),
                 all_labels = nlohmann::json::array();
  for (int k = 0; k < p.layers; ++k) {
    layer.z_mm = (k + 1) * h;
    t.layers.push_back(layer);
    for (std::size_t i = 0; i < speeds.size(); ++i) {
      all_speeds.push_back(speeds[i]);
      all_flows.push_back(flows[i]);
      all_labels.push_back(labels[i]);
    }
  }
  t.derived = {{"test", "lines"},
               {"nozzle_mm", p.nozzle_mm},
               {"layer_height_mm", h},
               {"footprint_mm", {2 * mx + p.fiducial_mm, 2 * my + p.fiducial_mm}},
               {"height_mm", p.layers * h},
               {"lines", lines},
               {"fiducials", fiducials},
               {"spacing_mm", p.spacing_mm},
               {"stroke_speeds_mm_per_min", all_speeds},
               {"stroke_flows", all_flows},
               {"stroke_labels", all_labels}};
  return std::make_unique<slicer::ToolpathLayers>(std::move(t));
}

}  // namespace strand::patterns
