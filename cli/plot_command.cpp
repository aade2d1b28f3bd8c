// `strand plot DRAWING.svg --machine NAME -o OUT.gcode`: import, lay out, order, plan, emit,
// report; `--erase` also writes the wall robot's erase sweeps.
#include <iostream>
#include <memory>

#include "machines/erase_pattern.h"
#include "machines/gcode_format.h"
#include "machines/pen_emitter.h"
#include "machines/plotter_kinematics.h"
#include "postprocess/plot/pen_planner.h"
#include "postprocess/plot/plot_layout.h"
#include "postprocess/plot/stroke_ordering.h"
#include "cli/commands.h"
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
          {"fit", ParamType::Size2, "mm", "fit the drawing into WxH keeping its aspect, centred in the drawable area", 1e-3},
          {"scale", ParamType::Number, "", "times the SVG's physical size (ignored with --fit)", 0.0, true, 1e4, false, 1.0},
          {"offset", ParamType::NumberList, "mm", "X,Y shift after centring", std::nullopt, false, std::nullopt, false, nlohmann::json::array({0, 0})},
          {"tolerance", ParamType::Number, "mm", "end-to-end error bound: curve flattening + kinematic bow + rounding", 0.0, true, 5.0, false, 0.05},
          {"pens", ParamType::Text, "", "pen rules KEY=PEN,... (KEY: group id, Inkscape layer label or colour); default: groups m1..m4 -> pens 1..4, else pen 1", std::nullopt, false, std::nullopt, false, ""},
          {"hatch-angle", ParamType::Number, "deg", "angle of the hatch lines that fill filled shapes", -180.0, false, 180.0, false, 45.0},
      }};
  return kTable;
}

struct PlotArgs {
  std::string svg, machine = "xy-plotter-servo", output, report, erase;
  bool mirror = false, no_order = false;
  std::map<std::string, std::string> text;
  std::map<std::string, CLI::Option*> options;
};

std::string mm(double v) { return machines::fmt_fixed(v, 3); }

nlohmann::json travel_json(double paper_mm, double axes_len, double feed) {
  return {{"pen_up_mm", paper_mm}, {"pen_up_time_s", axes_len / (feed / 60.0)}};
}

int run_plot(const PlotArgs& a) {
  nlohmann::json given = nlohmann::json::object();
  for (const auto& d : plot_table().defs) {
    if (a.options.at(d.key)->count() > 0) given[d.key] = slicer::parse_param_text(plot_table(), d, a.text.at(d.key));
  }
  const nlohmann::json v = slicer::resolve_params(plot_table(), given);
  if (v.at("offset").size() != 2) throw InputError("plot.offset: must be X,Y (mm)");
  post::PlotOptions o;
  if (v.contains("fit")) o.fit_mm = slicer::Vec2(v["fit"][0].get<double>(), v["fit"][1].get<double>());
  o.scale = v.at("scale").get<double>();
  o.offset_mm = slicer::Vec2(v["offset"][0].get<double>(), v["offset"][1].get<double>());
  o.tolerance_mm = v.at("tolerance").get<double>();
  o.pens = v.at("pens").get<std::string>();
  o.hatch_angle_deg = v.at("hatch-angle").get<double>();
  o.mirror = a.mirror;
  o.order = !a.no_order;
  const machines::MachineProfile m = machines::load_profile(a.machine);
  const slicer::SvgDrawing drawing = slicer::import_svg(slicer::read_file(a.svg), a.svg);
  slicer::Toolpath t = post::layout_plot(drawing, m, o);

  const auto& setup = m.plotter.setup;
  const post::MetricMap metric = [&setup](const slicer::Vec2& p) { return machines::to_axes(setup, p); };
  auto& strokes = t.layers[0].strokes;
  const std::size_t strokes_in = strokes.size();
  const auto before = post::pen_up_travel(strokes, setup.home_mm, metric);
  if (o.order) {
    strokes = post::merge_touching(strokes, 0.2 * o.tolerance_mm * post::kFlattenShare);
    post::OrderOptions oo;
    oo.start_mm = setup.home_mm;
    oo.metric = metric;
    strokes = post::order_strokes(strokes, oo);
  }
  const auto after = post::pen_up_travel(strokes, setup.home_mm, metric);
  const slicer::MotionProgram program = post::plan_pen(t, m, o.tolerance_mm);
  const post::PenEstimate e = post::estimate_pen(program, m);
  const double feed = m.limits.travel_feed_mm_per_min;

  nlohmann::json report = {
      {"generator", "plot"}, {"input", a.svg}, {"machine", m.name}, {"gcode", a.output},
      {"kinematics", machines::to_string(setup.kind)},
      {"parameters", v}, {"mirror", a.mirror}, {"order", o.order},
      {"skipped_elements", drawing.skipped},
      {"strokes", {{"input", strokes_in}, {"after_merge", strokes.size()}}},
      {"pen_up_before_ordering", travel_json(before.first, before.second, feed)},
      {"pen_up_after_ordering", travel_json(after.first, after.second, feed)},
      {"estimate", {{"time_s", e.time_s}, {"draw_mm", e.draw_mm}, {"draw_mm_per_pen", e.draw_mm_per_pen},
                    {"pen_up_mm", e.pen_up_mm}, {"pen_up_time_s", e.pen_up_time_s},
                    {"pen_lifts", e.pen_lifts}, {"size_mm", {e.size_mm.x(), e.size_mm.y()}}}},
      {"warnings", e.warnings}};
  const auto [alo, ahi] = machines::drawable_area(m.plotter);
  report["drawable_area_mm"] = {{alo.x(), alo.y()}, {ahi.x(), ahi.y()}};
  std::vector<std::string> header = {
      "Strand plot (SVG to pen G-code)", "input: " + a.svg,
      "machine: " + m.name + ", kinematics " + machines::to_string(setup.kind) + ", firmware " + machines::to_string(m.firmware),
      "tolerance: " + slicer::short_number(o.tolerance_mm) + " mm end to end (flattening, kinematic bow, rounding)",
      "size: " + mm(e.size_mm.x()) + " x " + mm(e.size_mm.y()) + " mm, scale " + machines::fmt_fixed(t.derived["scale"].get<double>(), 4),
      "strokes: " + std::to_string(strokes_in) + " in, " + std::to_string(strokes.size()) + " after merging",
      "pen-up travel: " + mm(before.first) + " mm before ordering, " + mm(after.first) + " mm after",
      "estimate: " + machines::fmt_fixed(e.time_s, 1) + " s, drawn " + mm(e.draw_mm) + " mm, " + std::to_string(e.pen_lifts) + " pen lifts"};
  for (const auto& s : drawing.skipped) header.push_back("skipped: " + s);
  for (const auto& w : e.warnings) header.push_back("warning: " + w);
  header.push_back("");
  const std::string gcode = machines::emit_pen_gcode(program, m, header);
  std::string erase;
  if (!a.erase.empty()) {
    const auto [lo, hi] = slicer::bounds(t);
    erase = machines::emit_erase_gcode(m, lo, hi, {"Strand erase pattern for " + a.svg, ""});
  }
  slicer::write_file_atomic(a.output, gcode);
  if (!erase.empty()) slicer::write_file_atomic(a.erase, erase);
  if (!a.report.empty()) slicer::write_file_atomic(a.report, slicer::dump_json(report) + "\n");
  std::cout << "plot " << a.svg << " -> " << a.output << " (" << m.name << ")\n"
            << "  size           " << mm(e.size_mm.x()) << " x " << mm(e.size_mm.y()) << " mm\n"
            << "  strokes        " << strokes_in << " (" << strokes.size() << " after merging)\n"
            << "  pen-up travel  " << mm(before.first) << " mm -> " << mm(after.first) << " mm after ordering\n"
            << "  drawn          " << mm(e.draw_mm) << " mm, " << e.pen_lifts << " pen lifts\n"
            << "  time           " << machines::fmt_fixed(e.time_s, 1) << " s\n";
  for (const auto& s : drawing.skipped) std::cout << "  skipped        " << s << "\n";
  for (const auto& w : e.warnings) std::cout << "  warning        " << w << "\n";
  return 0;
}

}  // namespace

void add_plot_command(CLI::App& app, Action& action) {
  auto a = std::make_shared<PlotArgs>();
  CLI::App* sub = app.add_subcommand("plot", "SVG drawing -> pen plotter G-code");
  sub->add_option("drawing", a->svg, "SVG file")->required();
  sub->add_option("--machine", a->machine, "plotter profile name or path to a .json profile (default xy-plotter-servo)");
  sub->add_option("-o,--output", a->output, "G-code file to write")->required();
  sub->add_option("--report", a->report, "write a JSON report here");
  sub->add_option("--erase", a->erase, "also write the erase sweeps over the drawing here");
  sub->add_flag("--mirror", a->mirror, "mirror left-right (drawing on glass)");
  sub->add_flag("--no-order", a->no_order, "keep the SVG's stroke order (no merging or reordering)");
  for (const auto& d : plot_table().defs) {
    std::string help = d.help + (d.unit.empty() ? "" : " [" + d.unit + "]");
    if (!d.default_value.is_null()) help += " (default " + (d.default_value.is_string() ? d.default_value.get<std::string>() : d.default_value.dump()) + ")";
    a->options[d.key] = sub->add_option("--" + d.key, a->text[d.key], help);
  }
  sub->callback([&action, a] { action = [a] { return run_plot(*a); }; });
}

}  // namespace strand::cli
