// Missing-rib parameters: the table behind `strand missing-rib` flags and job keys, and the
// rules that tie them together (ribs long enough that filaments keep a nozzle apart).
#include <algorithm>
#include <cmath>

#include "patterns/missing_rib.h"
#include "patterns/layer_params.h"
#include "slicer/input_error.h"
#include "slicer/units.h"

namespace strand::patterns {

using slicer::ParamDef;
using slicer::ParamType;

const slicer::ParamTable& missing_rib_table() {
  static const slicer::ParamTable kTable = with_layer_rows({
      "missing-rib",
      {
          {"nozzle", ParamType::Number, "mm", "filament (nozzle) diameter d; required", 0.0, true, 10.0},
          {"rib", ParamType::Number, "mm", "rib length, node to bend; required", 0.0, true, 1000.0},
          {"angle", ParamType::Number, "deg", "rib angle theta: nodes are rotated alternately by +theta and -theta", 0.0, true, 45.0, true, 20.0},
          {"node-gap", ParamType::Number, "mm", "distance between the two passes that turn at a node (their corners are cut); 0 = they meet on the node, nozzle = beads touch side by side", 0.0, false, 10.0, false, nullptr, "nozzle"},
          {"rows", ParamType::Integer, "", "cells along y", 1.0, false, 1000.0, false, 4},
          {"cols", ParamType::Integer, "", "cells along x", 1.0, false, 1000.0, false, 4},
          {"ligament-speed-factor", ParamType::Number, "", "speed factor on ribs (the frame runs at --speed)", 0.0, true, 10.0, false, 1.0},
      }}, "0.8 * nozzle");
  return kTable;
}

namespace {

const char* kName = "missing-rib";

// Node gap within the nozzle, and ribs long enough that filaments which are not joined
// stay a nozzle apart.
void check_rib(const nlohmann::json& v, const MissingRibParams& p, std::vector<std::string>& problems) {
  const double d = p.nozzle_mm;
  if (p.node_gap_mm > d + 1e-12) {
    problems.push_back(slicer::problem(kName, "node-gap", v.at("node-gap"),
                                       "must be in [0, nozzle] = [0, " + slicer::short_number(d) +
                                           "] so the passes at a node still touch",
                                       "mm"));
  }
  const double min_rib = missing_rib_min_rib_mm(p);
  if (p.rib_mm < min_rib - 1e-12) {
    problems.push_back(slicer::problem(
        kName, "rib", v.at("rib"),
        "must be >= " + slicer::short_number(std::ceil(min_rib * 1e4) / 1e4) + " at nozzle " + slicer::short_number(d) +
            " and angle " + slicer::short_number(p.angle_deg) +
            " deg = max(nozzle / (cos - sin), nozzle / cos + node-gap / sqrt 2), so filaments that are not joined stay a nozzle apart",
        "mm"));
  }
}

}  // namespace

double missing_rib_min_rib_mm(const MissingRibParams& p) {
  // Bends of a cell, and outer bends and the frame, stay a nozzle apart: d / (cos - sin).
  // What is left of a rib after the corner cut at its node (node gap / sqrt 2) spans at least
  // a nozzle across, so a frame piece or rib never runs alongside the cut: d / cos + gap / sqrt 2.
  const double d = p.nozzle_mm, theta = slicer::deg_to_rad(p.angle_deg);
  return std::max(d / (std::cos(theta) - std::sin(theta)),
                  d / std::cos(theta) + p.node_gap_mm / std::sqrt(2.0));
}

MissingRibParams missing_rib_params_from(const nlohmann::json& v) {
  std::vector<std::string> problems;
  if (!v.contains("nozzle")) problems.push_back("missing-rib.nozzle: missing (required, > 0 mm)");
  if (!v.contains("rib")) problems.push_back("missing-rib.rib: missing (required, > 0 mm)");
  require_one_of(kName, v, "height", "layers", problems);
  if (!problems.empty()) throw InputError(problems);

  MissingRibParams p;
  p.nozzle_mm = v.at("nozzle").get<double>();
  const double d = p.nozzle_mm;
  p.rib_mm = v.at("rib").get<double>();
  p.angle_deg = v.at("angle").get<double>();
  p.rows = v.at("rows").get<int>();
  p.cols = v.at("cols").get<int>();
  p.node_gap_mm = v.contains("node-gap") ? v.at("node-gap").get<double>() : d;
  check_rib(v, p, problems);
  const LayerStack stack = layer_stack_from(kName, v, d, 0.8, problems);
  p.layer_height_mm = stack.layer_height_mm;
  p.layers = stack.layers;
  p.speed_mm_per_min = v.at("speed").get<double>();
  if (!problems.empty()) throw InputError(problems);
  return p;
}

}  // namespace strand::patterns
