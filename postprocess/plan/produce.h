// One job end to end after generation: plan, estimate, emit G-code with its header, report.
#pragma once

#include <cstddef>
#include <memory>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>

#include "machines/profile.h"
#include "postprocess/plan/planner.h"
#include "slicer/layer_source.h"
#include "slicer/motion.h"
#include "slicer/progress_listener.h"
#include "slicer/toolpath.h"

namespace strand::post {

struct Produced {
  std::string gcode;         // empty when streamed (GcodeStreams)
  std::string viewer_gcode;  // preview-only copy with computed E; empty unless asked for
  // produce_layers with streams: the files' first lines, which go before the streamed bodies.
  std::string gcode_head;
  std::string viewer_gcode_head;
  nlohmann::json report;
  std::string summary;
  slicer::MotionProgram program;
};

// Where produce_layers writes the G-code bodies instead of Produced's strings: in blocks as
// they are formatted, so a large job never holds its whole file in memory.
struct GcodeStreams {
  std::ostream* gcode = nullptr;
  std::ostream* viewer_gcode = nullptr;  // used with viewer_e
};

// produce_layers for a toolpath already whole, in memory, the program kept: `gcode_path` is
// only recorded in the report; throws InputError if the part does not fit. With `viewer_e`,
// also the preview-only variant (machines::EmitOptions::viewer_e). The toolpath is taken by
// value and each layer released as it is planned (pass it with std::move).
Produced produce(slicer::Toolpath t, const machines::MachineProfile& m,
                 const PlanOptions& options, const std::string& gcode_path,
                 bool viewer_e = false, slicer::Progress* progress = nullptr);
// Options of produce_layers.
struct ProduceOptions {
  std::string gcode_path;  // only recorded in the report
  bool viewer_e = false;   // also the preview-only variant (machines::EmitOptions::viewer_e)
  // Null: the files are returned whole in Produced::gcode / viewer_gcode. Set: the streams
  // get each file's body (all but its head, which needs the totals) as it is formatted and
  // Produced::gcode_head / viewer_gcode_head the head that goes before it.
  GcodeStreams streams;
  slicer::Progress* progress = nullptr;  // told `phase`, a step per layer
  std::string phase = "planning and writing G-code";
  bool keep_program = false;              // also return the whole MotionProgram
};

// The job one layer at a time: each layer from the source is planned, estimated and written
// before the next is made, so memory does not grow with the job (only per-layer sums, the
// report and the header lines do). The bytes are those of produce_program() on the whole
// planned program.
// Throws InputError if the part does not fit (the streams then hold a partial body: write
// them to temp files that are dropped, slicer::OutputFiles).
Produced produce_layers(slicer::LayerSource& source, const machines::MachineProfile& m,
                        const PlanOptions& options, const ProduceOptions& produce_options);

// produce_layers with the layers handed in rather than asked for: add() them in order (one
// call at a time, from any thread), then finish(). What lets a job make its layers in
// parallel (jobs/slice_parallel.h) and still plan and write them in order, the same bytes.
class LayerProducer {
 public:
  // `record` is read again by finish() (its derived sizes complete by then); the references
  // must outlive the producer.
  LayerProducer(const slicer::Toolpath& record, std::size_t layers,
                const machines::MachineProfile& m, const PlanOptions& options,
                const ProduceOptions& produce_options);
  ~LayerProducer();
  LayerProducer(const LayerProducer&) = delete;
  LayerProducer& operator=(const LayerProducer&) = delete;
  // Plans, estimates and writes the next layer; the planned piece, valid until the next call.
  const slicer::MotionProgram& add(const slicer::Layer& layer);
  Produced finish();

 private:
  struct State;
  std::unique_ptr<State> s_;
};

// The same from an already planned whole program (conformal printing plans through a
// surface), in memory.
Produced produce_program(const slicer::Toolpath& t, slicer::MotionProgram program,
                         const machines::MachineProfile& m, const PlanOptions& options,
                         const std::string& gcode_path, bool viewer_e = false,
                         slicer::Progress* progress = nullptr);

}  // namespace strand::post
