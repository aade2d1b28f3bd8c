// `strand trace IMAGE -o OUT.svg`: a photo or scan traced with potrace into filled outlines,
// one Inkscape layer per grey level (m1, m2, ... so `strand plot` puts level k on pen k).
#include <iostream>
#include <memory>

#include "cli/commands.h"
#include "cli/output_path.h"
#include "cli/param_flags.h"
#include "cli/progress_bar.h"
#include "jobs/trace_input.h"
#include "machines/gcode_format.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"

namespace strand::cli {

using jobs::TracedImage;
using jobs::trace_file;
using jobs::trace_options;
using jobs::trace_table;

namespace {

struct TraceArgs {
  std::string image, output;
  ParamFlags flags;
};

int run_trace(TraceArgs a) {
  if (a.output.empty()) a.output = output_from_input(a.image, ".svg");  // img.png -> img.svg
  const nlohmann::json v = slicer::resolve_params(trace_table(), given_params(trace_table(), a.flags));
  const bool svg = a.output.size() >= 4 && a.output.compare(a.output.size() - 4, 4, ".svg") == 0;
  if (!svg) throw InputError("trace.output = " + a.output + ": must end in .svg (plot images with strand plot IMAGE --trace)");
  const auto progress = command_progress("trace", 3);
  const TracedImage t = trace_file(a.image, trace_options(v), progress.get());
  if (t.layers.empty()) throw InputError("trace: " + a.image + " has no pixel darker than the threshold (try --threshold)");
  slicer::OutputFiles out;
  out.protect_input(a.image);
  slicer::progress_phase(progress.get(), "writing the SVG");
  out.stage(a.output, slicer::write_svg_page(t.layers, t.trace.size_mm, 0.3));
  out.commit();
  if (progress) progress->finish();
  std::cout << "trace " << a.image << " -> " << a.output << "\n"
            << "  size           " << machines::fmt_fixed(t.trace.size_mm.x(), 3) << " x "
            << machines::fmt_fixed(t.trace.size_mm.y(), 3) << " mm\n"
            << "  traced         " << t.summary << "\n";
  return 0;
}

}  // namespace

void add_trace_command(CLI::App& app, Action& action) {
  auto a = std::make_shared<TraceArgs>();
  CLI::App* sub = app.add_subcommand("trace", "image (PNG, JPEG, PBM/PGM/PPM, ...) -> filled outlines in an SVG, with potrace");
  sub->add_option("image", a->image, "image file")->required();
  sub->add_option("-o,--output", a->output, "SVG file to write (mm; default: IMAGE's name with .svg)");
  add_param_flags(sub, trace_table(), a->flags);
  sub->callback([&action, a] { action = [a] { return run_trace(*a); }; });
}

}  // namespace strand::cli
