// Planning, estimating, header writing and emission for one toolpath.
#include "postprocess/plan/produce.h"

#include <memory>
#include <sstream>

#include "machines/gcode_emitter.h"
#include "machines/gcode_format.h"
#include "postprocess/plan/estimate.h"
#include "postprocess/plan/report.h"
#include "slicer/params.h"

namespace strand::post {

namespace {

std::vector<std::string> header(const slicer::Toolpath& t, const machines::MachineProfile& m,
                                const PlanOptions& o, const nlohmann::json& report) {
  std::vector<std::string> h;
  h.push_back("Strand " + t.generator + " (toolpaths for Direct Ink Writing)");
  h.push_back("machine: " + m.name + ", firmware " + machines::to_string(m.firmware) +
              ", deposition " + machines::to_string(m.deposition.model) +
              (m.arcs ? ", arcs as G2/G3" : ", arcs as G1 chords within " +
                                                slicer::short_number(o.arc_tolerance_mm) + " mm"));
  h.push_back("units: mm, mm/min");
  for (const auto& [k, v] : t.parameters.items()) h.push_back("param " + k + " = " + slicer::value_text(v));
  h.push_back("param arc-tolerance = " + slicer::short_number(o.arc_tolerance_mm));
  for (const auto& [k, v] : t.derived.items()) {
    if (v.is_number_float()) {
      h.push_back("derived " + k + " = " + machines::fmt_fixed(v.get<double>(), 4));
    } else {
      h.push_back("derived " + k + " = " + slicer::value_text(v));
    }
  }
  const auto& tot = report.at("totals");
  for (const char* k : {"layers", "deposit_length_mm", "travel_length_mm", "ink_volume_ml",
                        "reservoir_ml", "syringe_fills", "syringe_loads", "time_naive_s",
                        "time_trapezoid_s"}) {
    h.push_back("estimate " + std::string(k) + " = " + slicer::value_text(tot.at(k)));
  }
  for (const auto& l : report.at("layers")) {
    h.push_back("layer " + slicer::value_text(l.at("layer")) + ": length " + slicer::value_text(l.at("deposit_length_mm")) +
                " mm, ink " + slicer::value_text(l.at("volume_ml")) + " mL, time " + slicer::value_text(l.at("time_trapezoid_s")) +
                " s (naive " + slicer::value_text(l.at("time_naive_s")) + " s)");
  }
  h.push_back("");
  return h;
}

// The report and summary of a job from its estimates; returns the header's comment lines.
std::vector<std::string> report_job(Produced& out, const slicer::Toolpath& record,
                                    const machines::MachineProfile& m, const Estimate& e,
                                    const PlanOptions& options, const std::string& gcode_path) {
  out.report = make_report(record, m, e, gcode_path);
  out.report["parameters"]["arc-tolerance"] = options.arc_tolerance_mm;
  out.summary = summary_text(out.report);
  return header(record, m, options, out.report);
}

// One file's body (all but its head) going to a stream or kept in memory.
struct Body {
  Body(const machines::MachineProfile& m, const machines::EmitOptions& eo, std::ostream* stream)
      : writer(m, eo, stream ? *stream : memory) {}
  std::ostringstream memory;
  machines::GcodeBodyWriter writer;
};

}  // namespace

struct LayerProducer::State {
  State(const slicer::Toolpath& r, const machines::MachineProfile& machine, const PlanOptions& o,
        const ProduceOptions& p)
      : record(r), m(machine), options(o), po(p), planner(m, o), estimate(&m), gcode(m, eo, p.streams.gcode) {
    if (po.viewer_e) {
      machines::EmitOptions veo;
      veo.viewer_e = true;
      viewer = std::make_unique<Body>(m, veo, po.streams.viewer_gcode);
    }
  }
  const slicer::Toolpath& record;
  const machines::MachineProfile& m;
  PlanOptions options;
  ProduceOptions po;
  LayerPlanner planner;
  EstimateStream estimate;
  machines::EmitOptions eo;
  Body gcode;
  std::unique_ptr<Body> viewer;
  Produced out;
  std::size_t added = 0;
};

LayerProducer::LayerProducer(const slicer::Toolpath& record, std::size_t layers,
                             const machines::MachineProfile& m, const PlanOptions& options,
                             const ProduceOptions& po) {
  slicer::progress_phase(po.progress, po.phase, layers);
  s_ = std::make_unique<State>(record, m, options, po);
}

LayerProducer::~LayerProducer() = default;

const slicer::MotionProgram& LayerProducer::add(const slicer::Layer& layer) {
  State& s = *s_;
  const slicer::MotionProgram& piece = s.planner.plan(layer);
  s.estimate.add(piece);
  s.gcode.writer.add(piece);
  if (s.viewer) s.viewer->writer.add(piece);
  if (s.po.keep_program) slicer::append_piece(s.out.program, piece);
  slicer::progress_step(s.po.progress, ++s.added);
  return piece;
}

Produced LayerProducer::finish() {
  State& s = *s_;
  Produced& out = s.out;
  s.gcode.writer.finish();
  if (s.viewer) s.viewer->writer.finish();
  machines::EmitOptions eo = s.eo;
  eo.header = report_job(out, s.record, s.m, s.estimate.finish(), s.options, s.po.gcode_path);
  out.gcode_head = machines::gcode_head(s.m, eo);
  if (!s.po.streams.gcode) out.gcode = out.gcode_head + std::move(s.gcode.memory).str();
  if (s.viewer) {
    eo.viewer_e = true;
    out.viewer_gcode_head = machines::gcode_head(s.m, eo);
    if (!s.po.streams.viewer_gcode) out.viewer_gcode = out.viewer_gcode_head + std::move(s.viewer->memory).str();
  }
  return std::move(out);
}

Produced produce_layers(slicer::LayerSource& source, const machines::MachineProfile& m,
                        const PlanOptions& options, const ProduceOptions& po) {
  LayerProducer producer(source.record, source.layer_count(), m, options, po);
  for (std::size_t k = 0; k < source.layer_count(); ++k) producer.add(source.layer(k));
  return producer.finish();
}

Produced produce(slicer::Toolpath t, const machines::MachineProfile& m,
                 const PlanOptions& options, const std::string& gcode_path, bool viewer_e,
                 slicer::Progress* progress) {
  slicer::ToolpathLayers source(std::move(t));
  ProduceOptions po;
  po.gcode_path = gcode_path;
  po.viewer_e = viewer_e;
  po.progress = progress;
  po.keep_program = true;
  return produce_layers(source, m, options, po);
}

Produced produce_program(const slicer::Toolpath& t, slicer::MotionProgram program,
                         const machines::MachineProfile& m, const PlanOptions& options,
                         const std::string& gcode_path, bool viewer_e, slicer::Progress* progress) {
  Produced out;
  out.program = std::move(program);
  machines::EmitOptions eo;
  eo.header = report_job(out, t, m, estimate(out.program, m), options, gcode_path);
  slicer::progress_phase(progress, "writing G-code", out.program.moves.size());
  eo.progress = progress;
  out.gcode = machines::emit_gcode(out.program, m, eo);
  if (viewer_e) {
    eo.viewer_e = true;
    eo.progress = nullptr;
    out.viewer_gcode = machines::emit_gcode(out.program, m, eo);
  }
  return out;
}

}  // namespace strand::post
