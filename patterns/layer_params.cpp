// Shared layer-stack rules for the generators' parameter tables.
#include "patterns/layer_params.h"

#include <algorithm>
#include <cmath>

#include "slicer/params.h"

namespace strand::patterns {

slicer::ParamTable with_layer_rows(slicer::ParamTable t, const std::string& ratio_text) {
  using slicer::ParamType;
  t.defs.push_back({"height", ParamType::Number, "mm",
                    "part height, rounded to whole layers; give --height or --layers", 0.0, true,
                    10000.0});
  t.defs.push_back({"layers", ParamType::Integer, "", "number of layers; give --height or --layers",
                    1.0, false, 100000.0});
  t.defs.push_back({"layer-height", ParamType::Number, "mm",
                    "layer height h, allowed 0.5*nozzle to 1.0*nozzle", 0.0, true, 10.0, false,
                    nullptr, ratio_text});
  t.defs.push_back({"speed", ParamType::Number, "mm/min", "print speed", 0.0, true, 100000.0, false,
                    250.0});
  return t;
}

void require_one_of(const std::string& table, const nlohmann::json& v, const char* a,
                    const char* b, std::vector<std::string>& problems) {
  const bool has_a = v.contains(a);
  const bool has_b = v.contains(b);
  if (has_a && has_b) {
    problems.push_back(table + "." + a + ", " + table + "." + b + ": give exactly one of --" + a +
                       " or --" + b + ", not both");
  } else if (!has_a && !has_b) {
    problems.push_back(table + "." + a + ": missing (give --" + a + " or --" + b + ")");
  }
}

LayerStack layer_stack_from(const std::string& table, const nlohmann::json& v, double d,
                            double default_ratio, std::vector<std::string>& problems) {
  LayerStack s;
  s.layer_height_mm = v.contains("layer-height") ? v.at("layer-height").get<double>() : default_ratio * d;
  if (s.layer_height_mm < 0.5 * d - 1e-12 || s.layer_height_mm > d + 1e-12) {
    problems.push_back(slicer::problem(table, "layer-height", v.at("layer-height"),
                                       "must be in [0.5 * nozzle, 1.0 * nozzle] = [" +
                                           slicer::short_number(0.5 * d) + ", " +
                                           slicer::short_number(d) + "]",
                                       "mm"));
  }
  if (v.contains("layers")) {
    s.layers = v.at("layers").get<int>();
  } else {
    s.layers = std::max(1, static_cast<int>(std::lround(v.at("height").get<double>() / s.layer_height_mm)));
  }
  return s;
}

}  // namespace strand::patterns
