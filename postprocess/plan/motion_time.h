// Print time from a trapezoidal motion model: constant acceleration, a cruise at the
// programmed feed, and Marlin-style junction-deviation limits on the speed at corners.
#pragma once

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

// Highest speed through the corner between unit directions u1 then u2 (mm/s) by Marlin's
// junction deviation: sin(theta/2) = sqrt((1 - cos theta) / 2) with cos theta = -u1.u2,
// v = sqrt(a * jd * sin / (1 - sin)); unlimited (infinity) for a straight continuation, 0 for
// a reversal.
double junction_speed_mm_per_s(const slicer::Vec3& u1, const slicer::Vec3& u2,
                               double accel_mm_per_s2, double junction_deviation_mm);

// Time to cover `length_mm` entering at v_in, cruising at most at v_max and leaving at v_out
// with constant acceleration a (mm, mm/s, mm/s^2); v_in and v_out must be reachable.
double block_time_s(double length_mm, double v_in, double v_max, double v_out, double a);

}  // namespace strand::post
