// Valve lag: a pneumatic valve keeps pushing ink for lag_s after it closes, so it is closed
// that long before each strand ends.
#pragma once

#include "slicer/motion.h"

namespace strand::post {

// For every strand (a run of Deposit moves) lasting longer than lag_s at its feeds, splits
// the move where lag_s of motion remains and marks the moves after that point `coast`
// (the emitter closes the valve there). Shorter strands are left alone: the valve then
// closes at the strand's end.
void apply_valve_lag(slicer::MotionProgram& p, double lag_s);

}  // namespace strand::post
