// Re-entrant honeycomb parameters: the table behind `strand reentrant` flags and job keys,
// and the rules that tie them together (cells wide and tall enough for the nozzle).
#include <cmath>

#include "patterns/reentrant.h"
#include "patterns/layer_params.h"
#include "slicer/input_error.h"
#include "slicer/units.h"

namespace strand::patterns {

using slicer::ParamDef;
using slicer::ParamType;

const slicer::ParamTable& reentrant_table() {
  static const slicer::ParamTable kTable = with_layer_rows({
      "reentrant",
      {
          {"nozzle", ParamType::Number, "mm", "filament (nozzle) diameter d; required", 0.0, true, 10.0},
          {"cell-width", ParamType::Number, "mm", "distance between a cell's vertical ribs; required", 0.0, true, 1000.0},
          {"cell-height", ParamType::Number, "mm", "length of a cell's vertical ribs; required", 0.0, true, 1000.0},
          {"angle", ParamType::Number, "deg", "re-entrant angle: inclined ribs dip this far below horizontal into the cell", 0.0, true, 90.0, true, 20.0},
          {"rows", ParamType::Integer, "", "rows of cells, even", 2.0, false, 1000.0, false, 4},
          {"cols", ParamType::Integer, "", "full cells per odd row (even rows end in half cells)", 1.0, false, 1000.0, false, 4},
          {"ligament-speed-factor", ParamType::Number, "", "speed factor on ribs", 0.0, true, 10.0, false, 1.0},
      }}, "0.8 * nozzle");
  return kTable;
}

namespace {

const char* kName = "reentrant";

// Cell size and angle against the nozzle: a band's vertical ribs in consecutive rows stay
// a nozzle apart (W / 2 - d >= d), and so do the two re-entrant tips of a cell (H - W tan >= d).
void check_cell(const nlohmann::json& v, const ReentrantParams& p, std::vector<std::string>& problems) {
  const double d = p.nozzle_mm;
  const double min_width = p.cols >= 2 ? 4 * d : 3 * d;
  if (p.cell_width_mm < min_width - 1e-12) {
    problems.push_back(slicer::problem(kName, "cell-width", v.at("cell-width"),
                                       "must be >= " + std::string(p.cols >= 2 ? "4" : "3") + " * nozzle = " +
                                           slicer::short_number(min_width) +
                                           " so vertical ribs of neighbouring rows keep a nozzle apart",
                                       "mm"));
    return;
  }
  if (p.cell_height_mm <= d) {
    problems.push_back(slicer::problem(kName, "cell-height", v.at("cell-height"),
                                       "must be > nozzle = " + slicer::short_number(d) +
                                           " so the re-entrant tips can stay a nozzle apart", "mm"));
    return;
  }
  const double max_angle = slicer::rad_to_deg(std::atan((p.cell_height_mm - d) / p.cell_width_mm));
  if (p.angle_deg > std::floor(max_angle * 1e4) / 1e4 + 1e-12) {
    problems.push_back(slicer::problem(kName, "angle", v.at("angle"),
                                       "must be in (0, " + slicer::short_number(std::floor(max_angle * 1e4) / 1e4) +
                                           "] = (0, atan((cell-height - nozzle) / cell-width)] so a cell's "
                                           "re-entrant tips stay a nozzle apart",
                                       "deg"));
  }
}

}  // namespace

ReentrantParams reentrant_params_from(const nlohmann::json& v) {
  std::vector<std::string> problems;
  for (const char* key : {"nozzle", "cell-width", "cell-height"}) {
    if (!v.contains(key)) problems.push_back(std::string(kName) + "." + key + ": missing (required, > 0 mm)");
  }
  require_one_of(kName, v, "height", "layers", problems);
  if (!problems.empty()) throw InputError(problems);

  ReentrantParams p;
  p.nozzle_mm = v.at("nozzle").get<double>();
  const double d = p.nozzle_mm;
  p.cell_width_mm = v.at("cell-width").get<double>();
  p.cell_height_mm = v.at("cell-height").get<double>();
  p.angle_deg = v.at("angle").get<double>();
  p.rows = v.at("rows").get<int>();
  p.cols = v.at("cols").get<int>();
  if (p.rows % 2 != 0) {
    problems.push_back(slicer::problem(kName, "rows", v.at("rows"),
                                       "must be even so the bands join into one strand per layer", ""));
  }
  check_cell(v, p, problems);
  const LayerStack stack = layer_stack_from(kName, v, d, 0.8, problems);
  p.layer_height_mm = stack.layer_height_mm;
  p.layers = stack.layers;
  p.speed_mm_per_min = v.at("speed").get<double>();
  if (!problems.empty()) throw InputError(problems);
  return p;
}

}  // namespace strand::patterns
