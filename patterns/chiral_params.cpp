// Chiral specimen parameters: the table behind `strand tetrachiral` / `strand hexachiral`
// flags and job keys, and the rules that tie them together.
#include <cmath>

#include "patterns/chiral.h"
#include "patterns/layer_params.h"
#include "slicer/input_error.h"

namespace strand::patterns {

using slicer::ParamType;

slicer::ParamTable chiral_table(const std::string& name, double default_core_mm, int rows,
                                int cols) {
  return with_layer_rows({
      name,
      {
          {"nozzle", ParamType::Number, "mm", "filament (nozzle) diameter d; required", 0.0, true,
           10.0},
          {"cell", ParamType::Number, "mm", "node spacing l (centre to centre); required", 0.0,
           true, 1000.0},
          {"rows", ParamType::Integer, "", "cells along y (specimen length)", 2.0, false, 500.0,
           false, rows},
          {"cols", ParamType::Integer, "", "cells along x (specimen width)", 2.0, false, 500.0,
           false, cols},
          {"node-core", ParamType::Number, "mm",
           "hole inside the innermost node pass (node radius r = core/2 + h + d/2 for 3 passes)",
           0.0, true, 100.0, false, default_core_mm},
          {"node-passes", ParamType::Integer, "", "concentric passes per node visit, odd", 1.0,
           false, 15.0, false, 3},
          {"grip", ParamType::Number, "mm",
           "length of the solid zig-zag grip tab at each end, 0 = none", 0.0, false, 500.0, false,
           0.0},
          {"node-speed-factor", ParamType::Number, "",
           "speed factor of node passes (thesis: 10% faster to thin nodes)", 0.0, true, 10.0, false,
           1.10},
          {"ligament-speed-factor", ParamType::Number, "", "speed factor of ligaments", 0.0, true,
           10.0, false, 0.90},
      }}, "0.8 * nozzle");
}

ChiralParams chiral_params_from(ChiralKind kind, const std::string& name, const nlohmann::json& v) {
  std::vector<std::string> problems;
  if (!v.contains("nozzle")) problems.push_back(name + ".nozzle: missing (required, > 0 mm)");
  if (!v.contains("cell")) problems.push_back(name + ".cell: missing (required, > 0 mm)");
  require_one_of(name, v, "height", "layers", problems);
  if (!problems.empty()) throw InputError(problems);
  ChiralParams p;
  p.nozzle_mm = v.at("nozzle").get<double>();
  const double d = p.nozzle_mm;
  p.cell_mm = v.at("cell").get<double>();
  p.rows = v.at("rows").get<int>();
  p.cols = v.at("cols").get<int>();
  const LayerStack stack = layer_stack_from(name, v, d, 0.8, problems);
  p.layer_height_mm = stack.layer_height_mm;
  p.layers = stack.layers;
  p.core_mm = v.at("node-core").get<double>();
  p.passes = v.at("node-passes").get<int>();
  if (p.passes % 2 == 0) {
    problems.push_back(slicer::problem(
        name, "node-passes", p.passes,
        "must be odd (a visit enters and leaves at opposite ends of its sector)", ""));
  }
  p.grip_mm = v.at("grip").get<double>();
  if (p.grip_mm > 0 && p.grip_mm < 2 * d) {
    problems.push_back(
        slicer::problem(name, "grip", p.grip_mm,
                        "must be 0 or >= 2 * nozzle = " + slicer::short_number(2 * d), "mm"));
  }
  p.speed_mm_per_min = v.at("speed").get<double>();
  if (problems.empty()) {
    const double min_cell = chiral_min_cell_mm(kind, p);
    if (p.cell_mm < min_cell) {
      problems.push_back(slicer::problem(
          name, "cell", p.cell_mm,
          "must be >= " + slicer::short_number(min_cell) +
              " so ligaments are one nozzle long and clear the nodes and each other by one nozzle",
          "mm"));
    }
  }
  if (!problems.empty()) throw InputError(problems);
  return p;
}

}  // namespace strand::patterns
