// Layout, ordering, planning, emission, report and summary of one plot.
#include "jobs/plot_pipeline.h"

#include <sstream>

#include "machines/gcode_format.h"
#include "machines/pen_emitter.h"
#include "machines/plotter_kinematics.h"
#include "postprocess/plot/pen_planner.h"
#include "postprocess/plot/stroke_ordering.h"
#include "slicer/memory.h"
#include "slicer/params.h"

namespace strand::jobs {

namespace {

std::string mm(double v) { return machines::fmt_fixed(v, 3); }

nlohmann::json travel_json(double paper_mm, double axes_len, double feed) {
  return {{"pen_up_mm", paper_mm}, {"pen_up_time_s", axes_len / (feed / 60.0)}};
}

// Summary rows: a label padded to the value column, as every Strand command prints them.
std::string row(const std::string& label, const std::string& value) {
  std::string l = "  " + label;
  l.resize(std::max<std::size_t>(l.size() + 1, 17), ' ');
  return l + value + "\n";
}

// Stroke counts and pen-up travel (paper mm, axis-space length) before and after ordering.
struct Ordering {
  std::size_t strokes_in = 0, strokes_out = 0;
  std::pair<double, double> before, after;
};

nlohmann::json report_json(const PlotRequest& r, const machines::MachineProfile& m,
                           const post::PenEstimate& e, const Ordering& o) {
  const double feed = m.limits.travel_feed_mm_per_min;
  nlohmann::json report = {
      {"generator", "plot"}, {"input", r.input}, {"machine", m.name},
      {"kinematics", machines::to_string(m.plotter.setup.kind)},
      {"parameters", r.parameters}, {"mirror", r.options.mirror}, {"order", r.options.order},
      {"skipped_elements", r.drawing.skipped},
      {"strokes", {{"input", o.strokes_in}, {"after_merge", o.strokes_out}}},
      {"pen_up_before_ordering", travel_json(o.before.first, o.before.second, feed)},
      {"pen_up_after_ordering", travel_json(o.after.first, o.after.second, feed)},
      {"estimate", {{"time_s", e.time_s}, {"draw_mm", e.draw_mm}, {"draw_mm_per_pen", e.draw_mm_per_pen},
                    {"pen_up_mm", e.pen_up_mm}, {"pen_up_time_s", e.pen_up_time_s},
                    {"pen_lifts", e.pen_lifts}, {"size_mm", {e.size_mm.x(), e.size_mm.y()}}}},
      {"warnings", e.warnings}};
  for (const auto& [key, value] : r.notes) report["notes"][key] = value;
  const auto [alo, ahi] = machines::drawable_area(m.plotter);
  report["drawable_area_mm"] = {{alo.x(), alo.y()}, {ahi.x(), ahi.y()}};
  return report;
}

std::vector<std::string> header_lines(const PlotRequest& r, const machines::MachineProfile& m,
                                      const post::PenEstimate& e, const Ordering& o, double scale,
                                      const std::vector<std::string>& colours) {
  std::vector<std::string> header = {
      "Strand plot (drawing to pen G-code)", "input: " + r.input,
      "machine: " + m.name + ", kinematics " + machines::to_string(m.plotter.setup.kind) + ", firmware " + machines::to_string(m.firmware),
      "tolerance: " + slicer::short_number(r.options.tolerance_mm) + " mm end to end (flattening, kinematic bow, rounding)",
      "size: " + mm(e.size_mm.x()) + " x " + mm(e.size_mm.y()) + " mm, scale " + machines::fmt_fixed(scale, 4),
      "fill: " + post::to_string(r.options.fill),
      "strokes: " + std::to_string(o.strokes_in) + " in, " + std::to_string(o.strokes_out) + " after merging",
      "pen-up travel: " + mm(o.before.first) + " mm before ordering, " + mm(o.after.first) + " mm after",
      "estimate: " + machines::fmt_fixed(e.time_s, 1) + " s, drawn " + mm(e.draw_mm) + " mm, " + std::to_string(e.pen_lifts) + " pen lifts"};
  for (const auto& [key, value] : r.notes) header.push_back(key + ": " + value);
  for (const auto& s : r.drawing.skipped) header.push_back("skipped: " + s);
  for (const auto& w : e.warnings) header.push_back("warning: " + w);
  for (std::size_t k = 0; k < colours.size(); ++k) {  // read back by previews
    if (!colours[k].empty()) header.push_back("pen " + std::to_string(k + 1) + " colour: " + colours[k]);
  }
  header.push_back("");
  return header;
}

}  // namespace

void draw_text_into(PlotRequest& r, const slicer::TextOptions& o) {
  auto& d = r.drawing;
  if (d.texts.empty()) return;
  if (o.mode == slicer::TextMode::None) {
    d.skipped.insert(d.skipped.begin(), "text (" + std::to_string(d.texts.size()) + ")");
    return;
  }
  slicer::TextDrawing t = slicer::layout_text(d.texts, o);
  for (auto& s : t.shapes) d.shapes.push_back(std::move(s));
  r.notes.emplace_back("text", t.summary());
}

PlotResult plot_drawing(PlotRequest r, const machines::MachineProfile& m,
                        slicer::Progress* progress) {
  const post::PlotOptions& o = r.options;
  PlotResult out;
  slicer::progress_phase(progress, "laying out and filling");
  out.toolpath = post::layout_plot(r.drawing, m, o);
  std::vector<slicer::SvgShape>().swap(r.drawing.shapes);  // laid out: only `skipped` is read on
  slicer::release_free_memory();
  const auto& setup = m.plotter.setup;
  const post::MetricMap metric = [&setup](const slicer::Vec2& p) { return machines::to_axes(setup, p); };
  auto& strokes = out.toolpath.layers[0].strokes;
  const std::size_t strokes_in = strokes.size();
  const auto before = post::pen_up_travel(strokes, setup.home_mm, metric);
  if (o.order) {
    slicer::progress_phase(progress, "merging and ordering strokes");
    strokes = post::merge_touching(strokes, 0.2 * o.tolerance_mm * post::kFlattenShare);
    post::OrderOptions oo;
    oo.start_mm = setup.home_mm;
    oo.metric = metric;
    strokes = post::order_strokes(strokes, oo);
  }
  const auto after = post::pen_up_travel(strokes, setup.home_mm, metric);
  slicer::progress_phase(progress, "planning");
  const slicer::MotionProgram program = post::plan_pen(out.toolpath, m, o.tolerance_mm);
  const post::PenEstimate e = post::estimate_pen(program, m);

  const Ordering ord{strokes_in, strokes.size(), before, after};
  out.report = report_json(r, m, e, ord);
  const std::vector<std::string> header = header_lines(r, m, e, ord, out.toolpath.derived["scale"].get<double>(),
                   out.toolpath.derived["pen_colours"].get<std::vector<std::string>>());
  slicer::progress_phase(progress, "writing G-code");
  out.gcode = machines::emit_pen_gcode(program, m, header);

  std::ostringstream sum;
  sum << row("size", mm(e.size_mm.x()) + " x " + mm(e.size_mm.y()) + " mm")
      << row("strokes", std::to_string(strokes_in) + " (" + std::to_string(strokes.size()) + " after merging)")
      << row("pen-up travel", mm(before.first) + " mm -> " + mm(after.first) + " mm after ordering")
      << row("drawn", mm(e.draw_mm) + " mm, " + std::to_string(e.pen_lifts) + " pen lifts")
      << row("time", machines::fmt_fixed(e.time_s, 1) + " s");
  for (const auto& [key, value] : r.notes) sum << row(key, value);
  for (const auto& s : r.drawing.skipped) sum << row("skipped", s);
  for (const auto& w : e.warnings) sum << row("warning", w);
  out.summary = sum.str();
  return out;
}

}  // namespace strand::jobs
