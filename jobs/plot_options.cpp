// The plot parameter table and its values as options (see plot_options.h).
#include "jobs/plot_options.h"

#include "slicer/input_error.h"

namespace strand::jobs {

const slicer::ParamTable& plot_table() {
  using slicer::ParamType;
  static const slicer::ParamTable kTable{
      "plot",
      {
          {"fit", ParamType::Size2, "mm", "fit the drawing into WxH, or a paper (A0-A6, letter, legal, tabloid; portrait, or add landscape: \"A4 landscape\"), keeping its aspect, centred in the drawable area", 1e-3, false, std::nullopt, false, nullptr, "", {}, true},
          {"scale", ParamType::Number, "", "times the SVG's physical size (ignored with --fit)", 0.0, true, 1e4, false, 1.0},
          {"offset", ParamType::NumberList, "mm", "X,Y shift after centring", std::nullopt, false, std::nullopt, false, nlohmann::json::array({0, 0})},
          {"tolerance", ParamType::Number, "mm", "end-to-end error bound: curve flattening + kinematic bow + rounding", 0.001, false, 5.0, false, 0.05},
          {"pens", ParamType::Text, "", "pen rules KEY=PEN,... (KEY: group id, Inkscape layer label or colour); default: groups m1..m4 -> pens 1..4, else pen 1", std::nullopt, false, std::nullopt, false, ""},
          {"fill", ParamType::Text, "", "what a filled shape gets: its outline plus hatch lines or concentric rings, its outline only, or nothing", std::nullopt, false, std::nullopt, false, "hatch", "", {"hatch", "concentric", "outline", "none"}},
          {"hatch-angle", ParamType::NumberList, "deg", "angle of the hatch lines, one value or one per pen (pen 1 first, the last repeats)", -180.0, false, 180.0, false, nlohmann::json::array({45})},
          {"text", ParamType::Text, "", "how <text> is drawn: single-stroke Hershey font, the outline font the drawing names (fontconfig), or not at all", std::nullopt, false, std::nullopt, false, "hershey", "", {"hershey", "outline", "none"}},
          {"font", ParamType::Text, "", "hershey:NAME for --text hershey (futural, rowmans, scripts, timesr, ...); an installed family for --text outline (replaces the drawing's)", std::nullopt, false, std::nullopt, false, nullptr, "hershey:futural, or the drawing's own fonts"},
          {"text-width", ParamType::Text, "", "--text hershey: each glyph's own advance, or every run scaled across (not up) to the advance of the font the drawing names (fontconfig, FreeType) so lines stay as long as a browser draws them", std::nullopt, false, std::nullopt, false, "natural", "", {"natural", "fit"}},
          {"hatch-spacing", ParamType::NumberList, "mm", "distance between hatch lines or concentric rings, one value or one per pen", 0.0, true, std::nullopt, false, nullptr, "the pen width"},
      }};
  return kTable;
}

post::PlotOptions plot_options(const nlohmann::json& v, bool mirror, bool order) {
  if (v.at("offset").size() != 2) throw InputError("plot.offset: must be X,Y (mm)");
  post::PlotOptions o;
  if (v.contains("fit")) o.fit_mm = slicer::Vec2(v["fit"][0].get<double>(), v["fit"][1].get<double>());
  o.scale = v.at("scale").get<double>();
  o.offset_mm = slicer::Vec2(v["offset"][0].get<double>(), v["offset"][1].get<double>());
  o.tolerance_mm = v.at("tolerance").get<double>();
  o.pens = v.at("pens").get<std::string>();
  o.fill = post::fill_style_from_string(v.at("fill").get<std::string>());
  o.hatch_angle_deg = v.at("hatch-angle").get<std::vector<double>>();
  if (v.contains("hatch-spacing")) o.hatch_spacing_mm = v.at("hatch-spacing").get<std::vector<double>>();
  o.mirror = mirror;
  o.order = order;
  return o;
}

slicer::TextOptions text_options(const nlohmann::json& v) {
  slicer::TextOptions t;
  t.mode = slicer::text_mode_from_string(v.at("text").get<std::string>());
  if (v.contains("font")) t.font = v.at("font").get<std::string>();
  const bool hershey = !slicer::hershey_name(t.font).empty();
  if (t.mode == slicer::TextMode::Hershey && !t.font.empty() && !hershey) {
    throw InputError("plot.font = " + t.font + ": --text hershey needs hershey:NAME (or use --text outline for installed fonts)");
  }
  if (t.mode == slicer::TextMode::Outline && hershey) {
    throw InputError("plot.font = " + t.font + ": a Hershey font is single-stroke; use --text hershey with it");
  }
  t.fit_width = v.at("text-width").get<std::string>() == "fit";
  if (t.fit_width && t.mode == slicer::TextMode::Outline) {
    throw InputError("plot.text-width = fit: applies to --text hershey (outline letters have the font's own widths)");
  }
  return t;
}

void use_traced(PlotRequest& r, const TracedImage& t, const nlohmann::json& trace_resolved,
                bool hatch_angle_given, const std::string& label) {
  if (t.layers.empty()) throw InputError("trace: " + label + " has no pixel darker than the threshold (try --threshold)");
  r.drawing = drawing_of(t.layers, t.trace.size_mm);
  r.parameters["trace"] = trace_resolved;
  r.notes.emplace_back("traced", t.summary);
  if (!hatch_angle_given) {
    r.options.hatch_angle_deg.clear();
    const int n = static_cast<int>(t.trace.levels.size());
    for (int k = 0; k < n; ++k) r.options.hatch_angle_deg.push_back(45.0 + 180.0 * k / n);
  }
}

}  // namespace strand::jobs
