// `strand plot DRAWING.svg --machine NAME -o OUT.gcode`: import, lay out, order, plan, emit,
// report; `--erase` also writes the wall robot's erase sweeps.
#include <iostream>
#include <memory>
#include <utility>

#include "cli/commands.h"
#include "cli/output_path.h"
#include "cli/param_flags.h"
#include "cli/plot_pipeline.h"
#include "cli/progress.h"
#include "cli/trace_input.h"
#include "machines/erase_pattern.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"
#include "slicer/json_input.h"
#include "slicer/params.h"
#include "slicer/svg_import.h"

namespace strand::cli {

namespace {

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

struct PlotArgs {
  std::string svg, machine = "xy-plotter-servo", output, report, erase;
  bool mirror = false, no_order = false, trace = false;
  ParamFlags flags, trace_flags;
};

post::PlotOptions plot_options(const nlohmann::json& v, const PlotArgs& a) {
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
  o.mirror = a.mirror;
  o.order = !a.no_order;
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

// The image traced into pen layers; unless the user chose hatch angles, level k hatches at
// 45 + 180 (k - 1) / N degrees so that darker areas, covered by more levels, cross-hatch.
void read_traced(const PlotArgs& a, PlotRequest& r, slicer::Progress* progress) {
  const nlohmann::json tv = slicer::resolve_params(trace_table(), given_params(trace_table(), a.trace_flags));
  const TracedImage t = trace_file(a.svg, trace_options(tv), progress);
  if (t.layers.empty()) throw InputError("trace: " + a.svg + " has no pixel darker than the threshold (try --threshold)");
  r.drawing = drawing_of(t.layers, t.trace.size_mm);
  r.parameters["trace"] = tv;
  r.notes.emplace_back("traced", t.summary);
  if (a.flags.options.at("hatch-angle")->count() == 0) {
    r.options.hatch_angle_deg.clear();
    const int n = static_cast<int>(t.trace.levels.size());
    for (int k = 0; k < n; ++k) r.options.hatch_angle_deg.push_back(45.0 + 180.0 * k / n);
  }
}

int run_plot(PlotArgs a) {
  if (a.output.empty()) a.output = output_from_input(a.svg, ".gcode");  // drawing.svg -> drawing.gcode
  const auto progress = command_progress("plot", a.trace ? 7 : 6);
  PlotRequest r;
  r.parameters = slicer::resolve_params(plot_table(), given_params(plot_table(), a.flags));
  r.options = plot_options(r.parameters, a);
  r.input = a.svg;
  const machines::MachineProfile m = machines::load_profile(a.machine);
  if (a.trace) {
    read_traced(a, r, progress.get());
  } else {
    slicer::progress_phase(progress.get(), "reading the drawing");
    const nlohmann::json trace_given = given_params(trace_table(), a.trace_flags);
    if (!trace_given.empty()) throw InputError("trace." + trace_given.begin().key() + ": applies to images; add --trace");
    r.drawing = slicer::import_svg(slicer::read_file(a.svg), a.svg);
    if (!r.drawing.texts.empty()) slicer::progress_phase(progress.get(), "lettering");
    draw_text_into(r, text_options(r.parameters));
  }
  PlotResult p = plot_drawing(std::move(r), m, progress.get());
  p.report["gcode"] = a.output;
  std::string erase;
  if (!a.erase.empty()) {
    const auto [lo, hi] = slicer::bounds(p.toolpath);
    erase = machines::emit_erase_gcode(m, lo, hi, {"Strand erase pattern for " + a.svg, ""});
  }
  slicer::OutputFiles out;
  out.protect_input(a.svg);
  out.stage(a.output, p.gcode);
  if (!erase.empty()) out.stage(a.erase, erase);
  if (!a.report.empty()) out.stage(a.report, slicer::dump_json(p.report) + "\n");
  slicer::progress_phase(progress.get(), "writing files");
  out.commit();
  if (progress) progress->finish();
  std::cout << "plot " << a.svg << " -> " << a.output << " (" << m.name << ")\n" << p.summary;
  return 0;
}

}  // namespace

void add_plot_command(CLI::App& app, Action& action) {
  auto a = std::make_shared<PlotArgs>();
  CLI::App* sub = app.add_subcommand("plot", "SVG drawing -> pen plotter G-code");
  sub->add_option("drawing", a->svg, "SVG file (an image with --trace)")->required();
  sub->add_option("--machine", a->machine, "plotter profile name or path to a .json profile (default xy-plotter-servo)");
  sub->add_option("-o,--output", a->output, "G-code file to write (default: DRAWING's name with .gcode)");
  sub->add_option("--report", a->report, "write a JSON report here");
  sub->add_option("--erase", a->erase, "also write the erase sweeps over the drawing here");
  sub->add_flag("--mirror", a->mirror, "mirror left-right (drawing on glass)");
  sub->add_flag("--no-order", a->no_order, "keep the SVG's stroke order (no merging or reordering)");
  sub->add_flag("--trace", a->trace, "the drawing is an image (PNG, JPEG, PBM/PGM/PPM, ...): trace it with potrace, level k on pen k");
  add_param_flags(sub, plot_table(), a->flags);
  add_param_flags(sub, trace_table(), a->trace_flags);
  sub->callback([&action, a] { action = [a] { return run_plot(*a); }; });
}

}  // namespace strand::cli
