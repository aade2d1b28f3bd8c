// `strand plot DRAWING.svg --machine NAME -o OUT.gcode`: import, lay out, order, plan, emit,
// report; `--erase` also writes the wall robot's erase sweeps.
#include <iostream>
#include <memory>
#include <utility>

#include "cli/commands.h"
#include "cli/output_path.h"
#include "cli/param_flags.h"
#include "cli/progress_bar.h"
#include "jobs/plot_options.h"
#include "jobs/plot_pipeline.h"
#include "jobs/trace_input.h"
#include "machines/erase_pattern.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"
#include "slicer/json_input.h"
#include "slicer/params.h"
#include "slicer/svg_import.h"

namespace strand::cli {

using jobs::PlotRequest;
using jobs::PlotResult;
using jobs::TracedImage;
using jobs::draw_text_into;
using jobs::plot_drawing;
using jobs::plot_options;
using jobs::plot_table;
using jobs::text_options;
using jobs::trace_file;
using jobs::trace_options;
using jobs::trace_table;
using jobs::use_traced;

namespace {

struct PlotArgs {
  std::string svg, machine = "xy-plotter-servo", output, report, erase;
  bool mirror = false, no_order = false, trace = false;
  ParamFlags flags, trace_flags;
};

// The image traced into pen layers (plot_options.h: use_traced).
void read_traced(const PlotArgs& a, PlotRequest& r, slicer::Progress* progress) {
  const nlohmann::json tv = slicer::resolve_params(trace_table(), given_params(trace_table(), a.trace_flags));
  const TracedImage t = trace_file(a.svg, trace_options(tv), progress);
  use_traced(r, t, tv, a.flags.options.at("hatch-angle")->count() > 0, a.svg);
}

int run_plot(PlotArgs a) {
  if (a.output.empty()) a.output = output_from_input(a.svg, ".gcode");  // drawing.svg -> drawing.gcode
  const auto progress = command_progress("plot", a.trace ? 7 : 6);
  PlotRequest r;
  r.parameters = slicer::resolve_params(plot_table(), given_params(plot_table(), a.flags));
  r.options = plot_options(r.parameters, a.mirror, !a.no_order);
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
