// PoseProgram: the machine-level result for curved substrates, one timed pose per path point
// (the workpiece frame in the machine frame, the nozzle tip, the contact point and normal on
// the workpiece, speed, extrusion, layer, lap). Every writer for robots and rotary axes (pose
// CSV, KUKA Sunrise and KRL, rotary G-code, the extruder's E-only G-code) is a thin consumer
// of it, so all outputs share one time line.
#pragma once

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "slicer/geometry.h"
#include "slicer/toolpath.h"

namespace strand::slicer {

using Quat4 = Eigen::Vector4d;  // unit quaternion (w, x, y, z), w first

struct PosePoint {
  double t_s = 0.0;  // planned time when this point is reached
  // The workpiece frame in the machine frame (robot base, or the printer's own frame).
  Vec3 workpiece_origin_mm = Vec3::Zero();
  Quat4 workpiece_wxyz = Quat4(1, 0, 0, 0);
  Vec3 tip_mm = Vec3::Zero();      // the nozzle tip in the machine frame
  Vec3 contact_mm = Vec3::Zero();  // p: the nozzle tip in the workpiece frame
  Vec3 normal = Vec3::UnitX();     // n: outward surface normal at p, workpiece frame
  Vec2 uv_mm = Vec2::Zero();       // pattern coordinates; u unwrapped along the program
  double offset_mm = 0.0;          // nozzle tip above the substrate along the normal
  double turn_rad = 0.0;           // workpiece rotation about its axis, unwrapped
  double speed_mm_per_s = 0.0;     // planned contact speed from the previous point to here
  bool extrude = false;            // the motion from the previous point to here deposits
  int layer = 0;
  int lap = 0;  // global lap index (laps of all layers counted in order)
  Feature feature = Feature::Infill;

  bool operator==(const PosePoint&) const = default;
};

// A lap: a run of one layer that turns the workpiece one way (forward) or back (return).
struct PoseLap {
  int layer = 0;
  int direction = 1;          // +1 forward (turn growing), -1 return
  std::size_t first = 0;      // index of its first point in PoseProgram::points
  std::size_t last = 0;       // index of its last point (inclusive)
  double turn_min_rad = 0.0;  // turning range over the lap
  double turn_max_rad = 0.0;

  bool operator==(const PoseLap&) const = default;
};

struct PoseLayer {
  double offset_mm = 0.0;  // nozzle tip offset (k + 1) h
  double height_mm = 0.0;
  double u_stretch = 1.0;  // length on the deposited layer per mm of pattern u

  bool operator==(const PoseLayer&) const = default;
};

struct PoseProgram {
  std::vector<PosePoint> points;
  std::vector<PoseLap> laps;
  std::vector<PoseLayer> layers;
  nlohmann::json substrate;  // Surface::describe()

  bool operator==(const PoseProgram&) const = default;
};

}  // namespace strand::slicer
