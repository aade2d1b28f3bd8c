// Print time from a trapezoidal motion model: constant acceleration, a cruise at the
// programmed feed, and Marlin-style junction-deviation limits on the speed at corners.
#pragma once

#include <memory>
#include <vector>

#include "machines/profile.h"
#include "slicer/motion.h"

namespace strand::post {

struct TimeOptions {
  double acceleration_mm_per_s2 = 500.0;
  double junction_deviation_mm = 0.05;
  double max_feed_mm_per_min = 6000.0;
  // Valve machines send M400 before every valve command, so motion stops where the flow
  // starts or stops (travel <-> deposit, and at the lag close point).
  bool stop_at_flow_change = false;
  // Dwell the emitter adds at the start of every strand (valve lead time), s.
  double strand_start_dwell_s = 0.0;
  double arc_tolerance_mm = 0.01;  // arcs are timed as chords within this error
};

TimeOptions time_options_for(const machines::MachineProfile& m);

struct MotionTime {
  double total_s = 0.0;
  std::vector<double> layer_s;  // per MotionProgram layer; moves before layer 0 count in total only
};

MotionTime trapezoid_time(const slicer::MotionProgram& p, const TimeOptions& o);

// The same for a program that passes in pieces (one layer at a time, planner.h's
// LayerPlanner): add() each piece in order (start_mm is read from the first with moves; its
// layers list every layer so far), then finish() once. Memory is bounded by the distance
// between the planner's cuts, not by the program.
class TrapezoidTimer {
 public:
  explicit TrapezoidTimer(const TimeOptions& o);
  ~TrapezoidTimer();
  void add(const slicer::MotionProgram& piece);
  MotionTime finish();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Highest speed through the corner between unit directions u1 then u2 (mm/s) by Marlin's
// junction deviation: sin(theta/2) = sqrt((1 - cos theta) / 2) with cos theta = -u1.u2,
// v = sqrt(a * jd * sin / (1 - sin)); unlimited (infinity) for a straight continuation, 0 for
// a reversal.
double junction_speed_mm_per_s(const slicer::Vec3& u1, const slicer::Vec3& u2,
                               double accel_mm_per_s2, double junction_deviation_mm);

// Highest speed through the corner between unit directions u1 then u2 (mm/s) of a controller
// that blends within `blend_mm` of the corner (KRL C_DIS, Sunrise setBlendingCart, URScript r,
// RAPID zone): the arc tangent to both motions blend_mm before and after the corner has the
// radius blend / tan(theta / 2), theta the turn from u1 to u2, and is run at the centripetal
// limit v = sqrt(a * radius). Infinity straight on; 0 for a reversal or without blending. The
// same circle as junction_speed_mm_per_s, given by its tangent length instead of its deviation.
double blended_corner_speed_mm_per_s(const slicer::Vec3& u1, const slicer::Vec3& u2,
                                     double accel_mm_per_s2, double blend_mm);

// A straight block of a run that starts and ends at rest.
struct PathBlock {
  double length_mm = 0.0;
  double v_max = 0.0;             // cruise speed, mm/s
  double corner_limit = 0.0;      // speed limit at the corner into this block, mm/s
};

// Times of the blocks (s each), planned as a firmware or robot controller does: the backward
// pass lowers each corner to what the rest of the run can still stop from, the forward pass
// to what the acceleration reaches; the first block starts and the last ends at rest.
std::vector<double> rest_to_rest_times_s(const std::vector<PathBlock>& blocks,
                                         double accel_mm_per_s2);

// Time to cover `length_mm` entering at v_in, cruising at most at v_max and leaving at v_out
// with constant acceleration a (mm, mm/s, mm/s^2); v_in and v_out must be reachable.
double block_time_s(double length_mm, double v_in, double v_max, double v_out, double a);

}  // namespace strand::post
