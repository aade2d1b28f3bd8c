// Pore test: the table, the checked parameters and the log-pile.
#include "patterns/pore_test.h"

#include <algorithm>

#include "patterns/ink_test_marks.h"
#include "slicer/input_error.h"

namespace strand::patterns {

using slicer::ParamType;
using slicer::Vec2;

namespace {

// One layer's serpentine over the filament positions `at`, running from -reach to reach
// along x (`along_x`) or along y, turning outside the grid.
slicer::Stroke serpentine(const std::vector<double>& at, double reach, bool along_x, double width_mm,
                          double height_mm) {
  auto point = [&](double along, double across) { return along_x ? Vec2(along, across) : Vec2(across, along); };
  slicer::Stroke s;
  s.start_mm = point(-reach, at.front());
  for (std::size_t k = 0; k < at.size(); ++k) {
    const double to = k % 2 == 0 ? reach : -reach;
    if (k > 0) s.segments.push_back(slicer::line_to(point(-to, at[k]), slicer::Feature::Infill));
    s.segments.push_back(slicer::line_to(point(to, at[k]), slicer::Feature::Infill));
  }
  s.width_mm = width_mm;
  s.height_mm = height_mm;
  return s;
}

}  // namespace

const slicer::ParamTable& pore_test_table() {
  static const slicer::ParamTable kTable = {
      "pore-test",
      {
          {"nozzle", ParamType::Number, "mm", "nozzle diameter; required", 0.0, true, 10.0},
          {"pores", ParamType::Integer, "", "pores per side of the square grid", 1.0, false, 20.0, false, 4},
          {"pore-size", ParamType::Number, "mm", "open side of each square pore, between nozzle-wide filaments; at least the nozzle", 0.0, true, 50.0, false, nullptr, "3 * nozzle"},
          {"fiducial-size", ParamType::Number, "mm", "side of the square marks at the corners; at least 4 x nozzle", 0.0, true, 100.0, false, nullptr, "max(3, 5 * nozzle)"},
          {"layer-height", ParamType::Number, "mm", "layer height h, allowed 0.5*nozzle to 1.0*nozzle", 0.0, true, 10.0, false, nullptr, "0.8 * nozzle"},
          {"speed", ParamType::Number, "mm/min", "print speed", 0.0, true, 100000.0, false, 250.0},
          {"layers", ParamType::Integer, "", "layers, 0/90 alternately (a pore needs both directions)", 2.0, false, 200.0, false, 2},
      }};
  return kTable;
}

PoreTestParams pore_test_params_from(const nlohmann::json& v) {
  if (!v.contains("nozzle")) throw InputError("pore-test.nozzle: missing (required, > 0 mm)");
  std::vector<std::string> problems;
  PoreTestParams p;
  p.nozzle_mm = v.at("nozzle").get<double>();
  const double d = p.nozzle_mm;
  p.pores = v.at("pores").get<int>();
  p.pore_size_mm = v.contains("pore-size") ? v.at("pore-size").get<double>() : 3 * d;
  p.fiducial_mm = v.contains("fiducial-size") ? v.at("fiducial-size").get<double>() : std::max(3.0, 5 * d);
  p.layer_height_mm = v.contains("layer-height") ? v.at("layer-height").get<double>() : 0.8 * d;
  p.speed_mm_per_min = v.at("speed").get<double>();
  p.layers = v.at("layers").get<int>();
  if (p.pore_size_mm < d - 1e-9) {
    problems.push_back(slicer::problem("pore-test", "pore-size", p.pore_size_mm,
                                       "must be >= nozzle = " + slicer::short_number(d) + " (a pore a bead wide)", "mm"));
  }
  check_layer_and_marks("pore-test", d, p.layer_height_mm, p.fiducial_mm, problems);
  if (!problems.empty()) throw InputError(problems);
  return p;
}

std::unique_ptr<slicer::LayerSource> pore_test_layers(const PoreTestParams& p) {
  const double d = p.nozzle_mm, h = p.layer_height_mm;
  const double pitch = p.pore_size_mm + d;
  const int n = p.pores;
  std::vector<double> at;  // filament centres, both directions
  for (int k = 0; k <= n; ++k) at.push_back((k - n / 2.0) * pitch);
  const double reach = n / 2.0 * pitch + pitch / 2;  // where the serpentine turns

  nlohmann::json pores = nlohmann::json::array();
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      pores.push_back({{"index", pores.size()},
                       {"centre_mm", {(at[i] + at[i + 1]) / 2, (at[j] + at[j + 1]) / 2}},
                       {"side_mm", p.pore_size_mm}});
    }
  }
  // The marks clear of the turns by five nozzles, as the line matrix's by its spacing.
  const double m = reach + 5 * d + p.fiducial_mm / 2;
  slicer::Toolpath t;
  t.generator = "pore-test";
  nlohmann::json fiducials;
  for (int k = 0; k < p.layers; ++k) {
    slicer::Layer layer{(k + 1) * h, h, {}};
    layer.strokes.push_back(serpentine(at, reach, k % 2 == 0, d, h));
    if (k == 0) fiducials = add_corner_marks(layer, m, m, p.fiducial_mm, d, h);
    t.layers.push_back(std::move(layer));
  }
  t.derived = {{"test", "pore"},
               {"nozzle_mm", d},
               {"layer_height_mm", h},
               {"footprint_mm", {2 * m + p.fiducial_mm, 2 * m + p.fiducial_mm}},
               {"height_mm", p.layers * h},
               {"pitch_mm", pitch},
               {"pores", pores},
               {"fiducials", fiducials}};
  return std::make_unique<slicer::ToolpathLayers>(std::move(t));
}

}  // namespace strand::patterns
