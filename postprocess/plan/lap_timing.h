// Lap timing with the robot's corner slowdowns. The pose program's time line is distance /
// speed (what the pose CSV states and `strand check` verifies), but a robot only holds its
// Cartesian speed through a corner its blending rounds off: at a sharper corner it slows
// down, and every lap starts and ends at rest (the lap handshake). Each lap is planned here as
// a controller does (motion_time.h: acceleration, the arc its blending allows at each corner,
// backward and forward passes), which gives its real duration; the extruder's program follows
// that time line, so E per lap matches the lap the robot actually runs.
#pragma once

#include <nlohmann/json.hpp>
#include <vector>

#include "machines/profile.h"
#include "slicer/pose_program.h"

namespace strand::post {

struct CornerModel {
  double acceleration_mm_per_s2 = 500.0;  // path acceleration of the moved frame
  double blend_mm = 0.01;                 // blending distance before and after each corner
};

// The robot cell's model: machines::corner_acceleration_mm_per_s2 and the programs' blend
// (the arc tolerance: KRL $APO.CDIS, URScript r, RAPID zone). Precondition: m.robot.enabled.
CornerModel corner_model_for(const machines::MachineProfile& m, double blend_mm);

struct LapTiming {
  CornerModel model;
  // Per point: when the robot reaches it (each lap from rest to rest); t_s[0] = 0.
  std::vector<double> t_s;
  // Per lap (index = PosePoint::lap): the motions into the lap's points, as the robot runs
  // them from the lap's signal on.
  std::vector<double> nominal_s;  // distance / speed
  std::vector<double> planned_s;  // with the corner slowdowns
  std::vector<int> slowed_corners;  // corners taken below the lower neighbouring speed
  double nominal_total_s = 0.0;
  double planned_total_s = 0.0;
};

// Times every lap of `p`: blocks are the motions between consecutive points (zero-length ones
// take no time), grouped by the lap of the point they end at; a corner's blend is at most half
// of each neighbouring motion, as controllers shorten it.
LapTiming time_laps(const slicer::PoseProgram& p, const CornerModel& model);

// {"acceleration_mm_per_s2", "blend_mm", "nominal_s", "planned_s", "increase_percent",
//  "slowed_corners", "text"}; text: "laps timed with corner slowdowns: +4.2 % over
// distance/speed (...)".
nlohmann::json lap_timing_json(const LapTiming& timing);

}  // namespace strand::post
