// Chiral specimen parameters: the table behind `strand tetrachiral` / `strand hexachiral`
// flags and job keys, and the rules that tie them together.
#include <cmath>

#include "patterns/chiral.h"
#include "slicer/input_error.h"

namespace strand::patterns {

using slicer::ParamType;

slicer::ParamTable chiral_table(const std::string& name, double default_core_mm, int rows,
                                int cols) {
  return {
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
          {"height", ParamType::Number, "mm",
           "part height, rounded to whole layers; give --height or --layers", 0.0, true, 10000.0},
          {"layers", ParamType::Integer, "", "number of layers; give --height or --layers", 1.0,
           false, 100000.0},
          {"layer-height", ParamType::Number, "mm",
           "layer height h, allowed 0.5*nozzle to 1.0*nozzle", 0.0, true, 10.0, false, nullptr,
           "0.8 * nozzle"},
          {"node-core", ParamType::Number, "mm",
           "hole inside the innermost node pass (node radius r = core/2 + h + d/2 for 3 passes)",
           0.0, true, 100.0, false, default_core_mm},
          {"node-passes", ParamType::Integer, "", "concentric passes per node visit, odd", 1.0,
           false, 15.0, false, 3},
          {"grip", ParamType::Number, "mm",
           "length of the solid zig-zag grip tab at each end, 0 = none", 0.0, false, 500.0, false,
           0.0},
          {"speed", ParamType::Number, "mm/min", "print speed", 0.0, true, 100000.0, false, 250.0},
          {"node-speed-factor", ParamType::Number, "",
           "speed factor of node passes (thesis: 10% faster to thin nodes)", 0.0, true, 10.0, false,
           1.10},
          {"ligament-speed-factor", ParamType::Number, "", "speed factor of ligaments", 0.0, true,
           10.0, false, 0.90},
      }};
}

ChiralParams chiral_params_from(ChiralKind kind, const std::string& name, const nlohmann::json& v) {
  std::vector<std::string> problems;
  if (!v.contains("nozzle")) problems.push_back(name + ".nozzle: missing (required, > 0 mm)");
  if (!v.contains("cell")) problems.push_back(name + ".cell: missing (required, > 0 mm)");
  if (v.contains("height") == v.contains("layers")) {
    problems.push_back(name + ".layers: give exactly one of --height or --layers");
  }
  if (!problems.empty()) throw InputError(problems);
  ChiralParams p;
  p.nozzle_mm = v.at("nozzle").get<double>();
  const double d = p.nozzle_mm;
  p.cell_mm = v.at("cell").get<double>();
  p.rows = v.at("rows").get<int>();
  p.cols = v.at("cols").get<int>();
  p.layer_height_mm = v.contains("layer-height") ? v.at("layer-height").get<double>() : 0.8 * d;
  if (p.layer_height_mm < 0.5 * d - 1e-12 || p.layer_height_mm > d + 1e-12) {
    problems.push_back(slicer::problem(name, "layer-height", v.at("layer-height"),
                                       "must be in [0.5 * nozzle, 1.0 * nozzle] = [" +
                                           slicer::short_number(0.5 * d) + ", " +
                                           slicer::short_number(d) + "]",
                                       "mm"));
  }
  p.layers =
      v.contains("layers")
          ? v.at("layers").get<int>()
          : std::max(
                1, static_cast<int>(std::lround(v.at("height").get<double>() / p.layer_height_mm)));
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
