// Estimates from a MotionProgram: lengths, ink volume, strands and time per layer.
#pragma once

#include <memory>
#include <vector>

#include "machines/profile.h"
#include "slicer/motion.h"

namespace strand::post {

struct LayerEstimate {
  int layer = 0;
  double z_mm = 0.0;
  int strands = 0;               // uninterrupted deposit runs
  double deposit_length_mm = 0.0;
  double travel_length_mm = 0.0;
  double volume_mm3 = 0.0;
  double time_naive_s = 0.0;     // distance / feed
  double time_trapezoid_s = 0.0; // acceleration and junction limits (motion_time.h)
};

// What one printhead deposits (issue 33); time is its deposit moves' distance / feed.
struct ToolEstimate {
  int tool = 0;
  int strands = 0;
  double deposit_length_mm = 0.0;
  double volume_mm3 = 0.0;
  double time_naive_s = 0.0;
};

struct Estimate {
  std::vector<LayerEstimate> layers;
  double deposit_length_mm = 0.0;
  double travel_length_mm = 0.0;
  double volume_mm3 = 0.0;
  double time_naive_s = 0.0;     // sum of distance / feed, dwells included
  double time_trapezoid_s = 0.0; // 0 unless estimated for a machine
  std::vector<ToolEstimate> tools;  // by tool index, every tool up to the highest used
  int tool_changes = 0;             // moves whose tool differs from the move before
};

// Length of a move from `from` (arcs measured along the arc), mm.
double move_length(const slicer::Vec3& from, const slicer::Move& mv);
// Lengths, volumes, strands and the naive time only.
Estimate estimate(const slicer::MotionProgram& program);
// Also the trapezoidal time with the machine's limits; valve lead dwells (one per strand)
// count in both times.
Estimate estimate(const slicer::MotionProgram& program, const machines::MachineProfile& m);

// The same sums for a program that passes in pieces (one layer at a time: planner.h's
// LayerPlanner): add() each piece in order, then finish() once. With a machine (not null,
// outliving the stream) the trapezoidal time too. Only per-layer sums are kept.
class EstimateStream {
 public:
  explicit EstimateStream(const machines::MachineProfile* m);
  ~EstimateStream();
  void add(const slicer::MotionProgram& piece);
  Estimate finish();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace strand::post
