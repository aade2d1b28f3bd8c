// Scaffold parameters: the table behind `strand scaffold` flags and job keys, and the
// rules that tie them together.
#include <cmath>

#include "patterns/scaffold.h"
#include "patterns/layer_params.h"
#include "patterns/scaffold_plan.h"
#include "patterns/scaffold_schedule.h"
#include "slicer/input_error.h"

namespace strand::patterns {

using slicer::ParamDef;
using slicer::ParamType;

const slicer::ParamTable& scaffold_table() {
  static const slicer::ParamTable kTable = with_layer_rows({
      "scaffold",
      {
          {"nozzle", ParamType::Number, "mm", "filament (nozzle) diameter d; required", 0.0, true, 10.0},
          {"gap", ParamType::Number, "mm", "edge-to-edge gap between filaments (the thesis' l); give --gap or --pitch; with --grade also a..b (linear) or a,b,c (zones)", 0.0, false, 100.0, false, nullptr, "", {}, false, true},
          {"pitch", ParamType::Number, "mm", "centre-to-centre spacing = gap + nozzle; give --gap or --pitch", 0.0, true, 100.0},
          {"size", ParamType::Size2, "mm", "lattice footprint WxD without the overhang, rounded to whole pitches; required", 0.0, true, 10000.0},
          {"overhang", ParamType::Number, "mm", "how far U-turns stick out of the footprint", 0.0, false, 100.0, false, nullptr, "nozzle"},
          {"angles", ParamType::NumberList, "deg", "lay-down angles cycled per layer", -360.0, false, 360.0, false, "0,90"},
          {"grade", ParamType::Text, "", "axis along which a graded --gap varies", std::nullopt, false, std::nullopt, false, nullptr, "none", {"x", "y", "z"}},
          {"stagger", ParamType::Switch, "", "offset every second layer of the same direction by half a pitch", std::nullopt, false, std::nullopt, false, nullptr, "off"},
      }}, "0.88 * nozzle");
  return kTable;
}

namespace {

// --gap given as from..to ({"from", "to"}) or a list of zones, with --grade naming the axis.
GapGrade grade_from(const nlohmann::json& v, std::vector<std::string>& problems) {
  GapGrade g;
  const nlohmann::json& gap = v.at("gap");
  g.linear = gap.is_object();
  g.gaps_mm = g.linear ? std::vector<double>{gap.at("from").get<double>(), gap.at("to").get<double>()}
                       : gap.get<std::vector<double>>();
  const std::string axis = v.value("grade", std::string());
  g.axis = axis == "x" ? GradeAxis::X : axis == "y" ? GradeAxis::Y : axis == "z" ? GradeAxis::Z : GradeAxis::None;
  if (g.axis == GradeAxis::None) {
    problems.push_back("scaffold.gap = " + slicer::value_text(gap) +
                       ": a graded gap needs --grade x, y or z (the axis it varies along)");
  }
  return g;
}

// What a schedule may not do: grade the gap twice, or lay beads narrower than a layer or
// wider than the spacing.
void check_schedule(const ScaffoldParams& p, std::vector<std::string>& problems) {
  for (const auto& e : p.schedule) {
    const std::string at = "scaffold.schedule[" + std::to_string(e.first) + "-" + std::to_string(e.last) + "]";
    if (e.gap_mm && p.grade.axis != GradeAxis::None) {
      problems.push_back(at + ".gap = " + slicer::short_number(*e.gap_mm) +
                         ": the gap is already graded (--grade); give one or the other");
    }
    if (!e.flow) continue;
    const double w = flow_width_mm(p.nozzle_mm, p.layer_height_mm, *e.flow);
    const double pitch = e.gap_mm ? p.nozzle_mm + *e.gap_mm : p.pitch_mm;
    if (w < p.layer_height_mm || w > pitch) {
      problems.push_back(at + ".flow = " + slicer::short_number(*e.flow) + ": gives beads " +
                         slicer::short_number(std::round(w * 1000) / 1000) + " mm wide; must be in [" +
                         slicer::short_number(p.layer_height_mm) + ", " + slicer::short_number(pitch) +
                         "] (layer height to pitch)");
    }
  }
}

}  // namespace

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
  if (v.contains("gap") && !v.at("gap").is_number()) {
    p.grade = grade_from(v, problems);
    p.pitch_mm = p.grade.mean_mm() + d;
  } else {
    p.pitch_mm = v.contains("pitch") ? v.at("pitch").get<double>() : v.at("gap").get<double>() + d;
    if (v.contains("grade")) {
      problems.push_back("scaffold.grade = " + v.at("grade").get<std::string>() +
                         ": needs a graded --gap, from..to (linear) or a list of zones (0.8,1.2,1.6)");
    }
  }
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
  p.stagger = v.value("stagger", false);
  if (v.contains("schedule")) {
    p.schedule = schedule_from(v.at("schedule"), p.layers, problems);
    check_schedule(p, problems);
  }
  if (!problems.empty()) throw InputError(problems);
  return p;
}

}  // namespace strand::patterns
