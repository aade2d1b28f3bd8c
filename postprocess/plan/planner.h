// Room postprocess/plan (library strand_plan; links slicer, machines): everything between a
// generator's Toolpath and the bytes of a job's files. It owns placement on the machine, arc
// segmentation with a bounded chord error, per-feature speeds, deposition (volumetric E,
// valves), travels, the motion-time and ink estimates, the G-code header and the report
// (produce.h runs one job end to end). Nothing here reads G-code back; that is inspect/.
//
// Planning: Toolpath (part frame) -> MotionProgram (machine frame). Places the part,
// segments arcs where the firmware forbids G2/G3, assigns per-feature speeds and deposit
// volumes, and adds travels (with a z lift) between strokes.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "machines/profile.h"
#include "postprocess/plan/tool_assignment.h"
#include "slicer/motion.h"
#include "slicer/toolpath.h"

namespace strand::post {

struct PlanOptions {
  double speed_mm_per_min = 250.0;          // base deposit speed
  double arc_tolerance_mm = 0.01;           // chord error when arcs are segmented
  std::map<slicer::Feature, double> speed_factors;  // missing feature = 1.0
  // Base speed of each stroke in print order, replacing speed_mm_per_min (the line-width
  // matrix prints every line at its own speed); strokes past the end use speed_mm_per_min.
  std::vector<double> stroke_speeds_mm_per_min;
  // Flow of each stroke in print order (the matrix's rows): on pneumatic machines a change
  // sets the pressure (machines/flow_change.h); E-driven machines take it from the bead.
  std::vector<double> stroke_flows;
  // A comment written before each stroke in print order ("line 4: 300 mm/min, flow 1.25").
  std::vector<std::string> stroke_labels;
  // The ink profile's flow (--material): E-driven machines push this times the volume,
  // pneumatic ones set it once before the first stroke. Strokes with stroke_flows keep theirs.
  std::optional<double> flow;
  // Printheads by feature or layer (--tools); empty: each stroke's own tool.
  ToolAssignment tools;
  // Idle heads against the beads (idle_heads.h), when the plan is final; false where the
  // caller moves the plan on and checks what it makes of it (plan_draped).
  bool check_idle_heads = true;
};

// Reads "speed" and "<feature>-speed-factor" from the toolpath's parameters and
// "stroke_speeds_mm_per_min", "stroke_flows" and "stroke_labels" from its derived values.
PlanOptions plan_options_from(const slicer::Toolpath& t, double arc_tolerance_mm);

// Plans the toolpath for the machine and checks the result fits its build volume
// (throws InputError otherwise).
slicer::MotionProgram plan(const slicer::Toolpath& t, const machines::MachineProfile& machine,
                           const PlanOptions& options);
// The same one layer at a time, for a toolpath that is never whole (slicer/layer_source.h):
// what crosses layers (the nozzle's position, the approach before the first layer) is kept,
// each layer's moves replace the last one's. The moves of plan() for the whole toolpath are
// the concatenation of these, layer by layer (a strand never spans layers: each layer starts
// with a travel to its z).
class LayerPlanner {
 public:
  LayerPlanner(const machines::MachineProfile& machine, const PlanOptions& options);
  ~LayerPlanner();
  // Plans the next layer: the returned program (valid until the next call) holds that
  // layer's moves, every layer's z and height so far (moves index them as in the whole
  // program) and, as start_mm, the position before its first move. Valve lag is applied;
  // throws InputError if a move leaves the build volume.
  const slicer::MotionProgram& plan(const slicer::Layer& layer);

 private:
  struct State;
  std::unique_ptr<State> s_;
};

}  // namespace strand::post
