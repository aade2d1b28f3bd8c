// Filament fusion test: the table, the checked parameters and the meander.
#include "patterns/fusion_test.h"

#include <algorithm>
#include <cmath>

#include "patterns/ink_test_marks.h"
#include "slicer/input_error.h"

namespace strand::patterns {

using slicer::ParamType;
using slicer::Vec2;

namespace {

constexpr int kMaxSpacings = 40;

std::vector<double> spacings_of(const FusionTestParams& p) {
  std::vector<double> s;
  for (int k = 0;; ++k) {
    const double v = p.spacing_start_mm - k * p.spacing_step_mm;
    if (v < p.spacing_end_mm - 1e-9 || k > kMaxSpacings) break;
    s.push_back(v);
  }
  return s;
}

// The measured zone keeps this far from each end of a filament: the U-turns' bulge stays out.
double turn_clearance_mm(const FusionTestParams& p) { return 2 * p.spacing_start_mm; }

}  // namespace

const slicer::ParamTable& fusion_test_table() {
  static const slicer::ParamTable kTable = {
      "fusion-test",
      {
          {"nozzle", ParamType::Number, "mm", "nozzle diameter; required", 0.0, true, 10.0},
          {"spacing-start", ParamType::Number, "mm", "centre-to-centre spacing of the first pair of filaments", 0.0, true, 50.0, false, nullptr, "4 * nozzle"},
          {"spacing-end", ParamType::Number, "mm", "spacing of the last pair; at least the nozzle", 0.0, true, 50.0, false, nullptr, "nozzle"},
          {"spacing-step", ParamType::Number, "mm", "how much the spacing shrinks from pair to pair", 0.0, true, 50.0, false, nullptr, "0.5 * nozzle"},
          {"length", ParamType::Number, "mm", "length of each filament; at least 4 x spacing-start + 2 x nozzle", 2.0, false, 200.0, false, 20.0},
          {"fiducial-size", ParamType::Number, "mm", "side of the square marks at the corners; at least 4 x nozzle", 0.0, true, 100.0, false, nullptr, "max(3, 5 * nozzle)"},
          {"layer-height", ParamType::Number, "mm", "layer height h, allowed 0.5*nozzle to 1.0*nozzle", 0.0, true, 10.0, false, nullptr, "0.8 * nozzle"},
          {"speed", ParamType::Number, "mm/min", "print speed", 0.0, true, 100000.0, false, 250.0},
          {"layers", ParamType::Integer, "", "layers of the same meander", 1.0, false, 50.0, false, 1},
      }};
  return kTable;
}

FusionTestParams fusion_test_params_from(const nlohmann::json& v) {
  if (!v.contains("nozzle")) throw InputError("fusion-test.nozzle: missing (required, > 0 mm)");
  std::vector<std::string> problems;
  FusionTestParams p;
  p.nozzle_mm = v.at("nozzle").get<double>();
  const double d = p.nozzle_mm;
  p.spacing_start_mm = v.contains("spacing-start") ? v.at("spacing-start").get<double>() : 4 * d;
  p.spacing_end_mm = v.contains("spacing-end") ? v.at("spacing-end").get<double>() : d;
  p.spacing_step_mm = v.contains("spacing-step") ? v.at("spacing-step").get<double>() : 0.5 * d;
  p.length_mm = v.at("length").get<double>();
  p.fiducial_mm = v.contains("fiducial-size") ? v.at("fiducial-size").get<double>() : std::max(3.0, 5 * d);
  p.layer_height_mm = v.contains("layer-height") ? v.at("layer-height").get<double>() : 0.8 * d;
  p.speed_mm_per_min = v.at("speed").get<double>();
  p.layers = v.at("layers").get<int>();
  if (p.spacing_end_mm < d - 1e-9) {
    problems.push_back(slicer::problem("fusion-test", "spacing-end", p.spacing_end_mm,
                                       "must be >= nozzle = " + slicer::short_number(d) + " (closer beads overlap by design)", "mm"));
  }
  if (p.spacing_start_mm < p.spacing_end_mm - 1e-9) {
    problems.push_back(slicer::problem("fusion-test", "spacing-start", p.spacing_start_mm,
                                       "must be >= spacing-end = " + slicer::short_number(p.spacing_end_mm) + " (the spacing shrinks)", "mm"));
  } else if (spacings_of(p).size() > static_cast<std::size_t>(kMaxSpacings)) {
    problems.push_back(slicer::problem("fusion-test", "spacing-step", p.spacing_step_mm,
                                       "gives more than " + std::to_string(kMaxSpacings) + " spacings from " +
                                           slicer::short_number(p.spacing_start_mm) + " to " + slicer::short_number(p.spacing_end_mm) +
                                           "; must be >= " + slicer::short_number((p.spacing_start_mm - p.spacing_end_mm) / (kMaxSpacings - 1)),
                                       "mm"));
  }
  const double least = 2 * turn_clearance_mm(p) + 2 * d;
  if (p.length_mm < least - 1e-9) {
    problems.push_back(slicer::problem("fusion-test", "length", p.length_mm,
                                       "must be >= 4 x spacing-start + 2 x nozzle = " + slicer::short_number(std::round(1e6 * least) / 1e6) +
                                           " (a measured zone clear of the U-turns)", "mm"));
  }
  check_layer_and_marks("fusion-test", d, p.layer_height_mm, p.fiducial_mm, problems);
  if (!problems.empty()) throw InputError(problems);
  return p;
}

std::unique_ptr<slicer::LayerSource> fusion_test_layers(const FusionTestParams& p) {
  const double d = p.nozzle_mm, h = p.layer_height_mm, half = p.length_mm / 2;
  const std::vector<double> gaps = spacings_of(p);
  std::vector<double> x = {0.0};
  for (double s : gaps) x.push_back(x.back() + s);
  const double shift = x.back() / 2;
  for (double& v : x) v -= shift;

  slicer::Stroke meander;
  meander.start_mm = Vec2(x[0], -half);
  meander.width_mm = d;
  meander.height_mm = h;
  for (std::size_t k = 0; k < x.size(); ++k) {
    const double to = k % 2 == 0 ? half : -half;
    if (k > 0) meander.segments.push_back(slicer::line_to(Vec2(x[k], -to), slicer::Feature::Infill));
    meander.segments.push_back(slicer::line_to(Vec2(x[k], to), slicer::Feature::Infill));
  }
  const double zone = half - turn_clearance_mm(p);
  nlohmann::json spacings = nlohmann::json::array();
  for (std::size_t k = 0; k < gaps.size(); ++k) {
    const double mid = (x[k] + x[k + 1]) / 2;
    spacings.push_back({{"index", k},
                        {"spacing_mm", gaps[k]},
                        {"filaments_x_mm", {x[k], x[k + 1]}},
                        {"start_mm", {mid, -zone}},
                        {"end_mm", {mid, zone}}});
  }
  const double mx = shift + 5 * d + p.fiducial_mm / 2, my = half + 5 * d + p.fiducial_mm / 2;
  slicer::Toolpath t;
  t.generator = "fusion-test";
  nlohmann::json fiducials;
  for (int k = 0; k < p.layers; ++k) {
    slicer::Layer layer{(k + 1) * h, h, {meander}};
    if (k == 0) fiducials = add_corner_marks(layer, mx, my, p.fiducial_mm, d, h);
    t.layers.push_back(std::move(layer));
  }
  t.derived = {{"test", "fusion"},
               {"nozzle_mm", d},
               {"layer_height_mm", h},
               {"footprint_mm", {2 * mx + p.fiducial_mm, 2 * my + p.fiducial_mm}},
               {"height_mm", p.layers * h},
               {"spacings", spacings},
               {"fiducials", fiducials}};
  return std::make_unique<slicer::ToolpathLayers>(std::move(t));
}

}  // namespace strand::patterns
