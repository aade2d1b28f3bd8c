// Scaffold parameters: the table behind `strand scaffold` flags and job keys, and the
// rules that tie them together.
#include <cmath>

#include "patterns/scaffold.h"
#include "patterns/layer_params.h"
#include "slicer/input_error.h"

namespace strand::patterns {

using slicer::ParamDef;
using slicer::ParamType;

const slicer::ParamTable& scaffold_table() {
  static const slicer::ParamTable kTable = with_layer_rows({
      "scaffold",
      {
          {"nozzle", ParamType::Number, "mm", "filament (nozzle) diameter d; required", 0.0, true, 10.0},
          {"gap", ParamType::Number, "mm", "edge-to-edge gap between filaments (the thesis' l); give --gap or --pitch", 0.0, false, 100.0},
          {"pitch", ParamType::Number, "mm", "centre-to-centre spacing = gap + nozzle; give --gap or --pitch", 0.0, true, 100.0},
          {"size", ParamType::Size2, "mm", "lattice footprint WxD without the overhang, rounded to whole pitches; required", 0.0, true, 10000.0},
          {"overhang", ParamType::Number, "mm", "how far U-turns stick out of the footprint", 0.0, false, 100.0, false, nullptr, "nozzle"},
          {"angles", ParamType::NumberList, "deg", "lay-down angles cycled per layer", -360.0, false, 360.0, false, "0,90"},
      }}, "0.88 * nozzle");
  return kTable;
}

ScaffoldParams scaffold_params_from(const nlohmann::json& v) {
  std::vector<std::string> problems;
  if (!v.contains("nozzle")) problems.push_back("scaffold.nozzle: missing (required, > 0 mm)");
  if (!v.contains("size")) problems.push_back("scaffold.size: missing (required, WxD in mm, each > 0)");
  require_one_of("scaffold", v, "gap", "pitch", problems);
  require_one_of("scaffold", v, "height", "layers", problems);
  if (!problems.empty()) throw InputError(problems);

  ScaffoldParams p;
  p.nozzle_mm = v.at("nozzle").get<double>();
  const double d = p.nozzle_mm;
  p.pitch_mm = v.contains("pitch") ? v.at("pitch").get<double>() : v.at("gap").get<double>() + d;
  if (p.pitch_mm < d) {
    problems.push_back(slicer::problem("scaffold", "pitch", v.at("pitch"),
                                       "must be >= nozzle = " + slicer::short_number(d) +
                                           " (filaments would overlap)", "mm"));
  }
  p.width_mm = v.at("size")[0].get<double>();
  p.depth_mm = v.at("size")[1].get<double>();
  for (double side : {p.width_mm, p.depth_mm}) {
    if (side < d) {
      problems.push_back(slicer::problem("scaffold", "size", v.at("size"),
                                         "each side must be >= nozzle = " + slicer::short_number(d), "mm"));
      break;
    }
  }
  const LayerStack stack = layer_stack_from("scaffold", v, d, 0.88, problems);
  p.layer_height_mm = stack.layer_height_mm;
  p.layers = stack.layers;
  p.overhang_mm = v.contains("overhang") ? v.at("overhang").get<double>() : d;
  p.angles_deg = v.at("angles").get<std::vector<double>>();
  p.speed_mm_per_min = v.at("speed").get<double>();
  if (!problems.empty()) throw InputError(problems);
  return p;
}

}  // namespace strand::patterns
