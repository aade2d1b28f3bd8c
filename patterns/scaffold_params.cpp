// Scaffold parameters: the table behind `strand scaffold` flags and job keys, and the
// rules that tie them together.
#include <cmath>

#include "patterns/scaffold.h"
#include "slicer/input_error.h"

namespace strand::patterns {

using slicer::ParamDef;
using slicer::ParamType;

const slicer::ParamTable& scaffold_table() {
  static const slicer::ParamTable kTable = {
      "scaffold",
      {
          {"nozzle", ParamType::Number, "mm", "filament (nozzle) diameter d; required", 0.0, true, 10.0},
          {"gap", ParamType::Number, "mm", "edge-to-edge gap between filaments (the thesis' l); give --gap or --pitch", 0.0, false, 100.0},
          {"pitch", ParamType::Number, "mm", "centre-to-centre spacing = gap + nozzle; give --gap or --pitch", 0.0, true, 100.0},
          {"size", ParamType::Size2, "mm", "lattice footprint WxD without the overhang, rounded to whole pitches; required", 0.0, true, 10000.0},
          {"height", ParamType::Number, "mm", "part height, rounded to whole layers; give --height or --layers", 0.0, true, 10000.0},
          {"layers", ParamType::Integer, "", "number of layers; give --height or --layers", 1.0, false, 100000.0},
          {"layer-height", ParamType::Number, "mm", "layer height h, allowed 0.5*nozzle to 1.0*nozzle", 0.0, true, 10.0, false, nullptr, "0.88 * nozzle"},
          {"overhang", ParamType::Number, "mm", "how far U-turns stick out of the footprint", 0.0, false, 100.0, false, nullptr, "nozzle"},
          {"angles", ParamType::NumberList, "deg", "lay-down angles cycled per layer", -360.0, false, 360.0, false, "0,90"},
          {"speed", ParamType::Number, "mm/min", "print speed", 0.0, true, 100000.0, false, 250.0},
      }};
  return kTable;
}

namespace {

void require_one_of(const nlohmann::json& v, const char* a, const char* b,
                    std::vector<std::string>& problems) {
  const bool has_a = v.contains(a);
  const bool has_b = v.contains(b);
  if (has_a && has_b) {
    problems.push_back(std::string("scaffold.") + a + ", scaffold." + b +
                       ": give exactly one of --" + a + " or --" + b + ", not both");
  } else if (!has_a && !has_b) {
    problems.push_back(std::string("scaffold.") + a + ": missing (give --" + a + " or --" + b + ")");
  }
}

}  // namespace

ScaffoldParams scaffold_params_from(const nlohmann::json& v) {
  std::vector<std::string> problems;
  if (!v.contains("nozzle")) problems.push_back("scaffold.nozzle: missing (required, > 0 mm)");
  if (!v.contains("size")) problems.push_back("scaffold.size: missing (required, WxD in mm, each > 0)");
  require_one_of(v, "gap", "pitch", problems);
  require_one_of(v, "height", "layers", problems);
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
  p.layer_height_mm = v.contains("layer-height") ? v.at("layer-height").get<double>() : 0.88 * d;
  if (p.layer_height_mm < 0.5 * d - 1e-12 || p.layer_height_mm > d + 1e-12) {
    problems.push_back(slicer::problem(
        "scaffold", "layer-height", v.at("layer-height"),
        "must be in [0.5 * nozzle, 1.0 * nozzle] = [" + slicer::short_number(0.5 * d) + ", " +
            slicer::short_number(d) + "]", "mm"));
  }
  if (v.contains("layers")) {
    p.layers = v.at("layers").get<int>();
  } else {
    p.layers = std::max(1, static_cast<int>(std::lround(v.at("height").get<double>() / p.layer_height_mm)));
  }
  p.overhang_mm = v.contains("overhang") ? v.at("overhang").get<double>() : d;
  p.angles_deg = v.at("angles").get<std::vector<double>>();
  p.speed_mm_per_min = v.at("speed").get<double>();
  if (!problems.empty()) throw InputError(problems);
  return p;
}

slicer::Toolpath scaffold_from_values(const nlohmann::json& values) {
  slicer::Toolpath t = generate_scaffold(scaffold_params_from(values));
  t.parameters = values;
  return t;
}

}  // namespace strand::patterns
