// Room postprocess/plot (library strand_plot; links slicer, machines): pen plotting after the
// SVG import. It owns the layout on the paper (plot_layout.h: pens, fit, flattening, hatch
// fills with Clipper), merging and ordering strokes to cut pen-up travel
// (stroke_ordering.h, point_grid.h) and this planner; the machine's own words stay in
// machines/pen_emitter.
//
// Planning for pen plotters: a plotting Toolpath -> MotionProgram in the paper frame (pen
// up/down as z 1/0 travels, dwells after servo moves, drawing as deposits split so the
// kinematic bow stays within budget), and the estimate computed from that same program.
#pragma once

#include <string>
#include <vector>

#include "machines/profile.h"
#include "slicer/motion.h"
#include "slicer/toolpath.h"

namespace strand::post {

// `tolerance_mm` is the end-to-end bound; the flattening share is already spent by the
// layout, the rest is split between number rounding and bow. Throws InputError when the
// tolerance is below what the machine's resolution allows, or a point cannot be reached.
slicer::MotionProgram plan_pen(const slicer::Toolpath& t, const machines::MachineProfile& m,
                               double tolerance_mm);

struct PenEstimate {
  double time_s = 0.0;               // moves (axis distance / feed) + pen moves + dwells
  double draw_mm = 0.0;              // pen-down length on paper
  double pen_up_mm = 0.0;            // pen-up travel on paper
  double pen_up_time_s = 0.0;
  int pen_lifts = 0;
  std::vector<double> draw_mm_per_pen;  // index = 0-based pen
  slicer::Vec2 size_mm = slicer::Vec2::Zero();  // extent of the drawn moves
  std::vector<std::string> warnings;  // pens past their capacity
};

PenEstimate estimate_pen(const slicer::MotionProgram& p, const machines::MachineProfile& m);

}  // namespace strand::post
