// The plotting part of a machine profile: how the pen is lifted and changed, and the
// plotter's own kinematics (XY, V-plotter on two cables, polar R-theta) with its paper frame.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "slicer/geometry.h"

namespace strand::machines {

enum class PlotterKind {
  Xy,          // G-code X/Y are paper millimetres (y up)
  Polargraph,  // G-code X/Y are the two cable lengths (paper y down from the motor line)
  PolarRTheta, // G-code X = radius travel, Y = angle lead-screw travel (paper y down)
};

enum class PenLift {
  Servo,  // M280 P<index> S<angle> (Marlin) or M3 S<value>/M5 (GRBL), then a dwell
  Z,      // Z axis: up/down heights
  Drum,   // Scribit drum on Z (degrees): engage / rest / write angles per marker
};

struct DrumAngles {
  double engage_step_deg = 60.0;  // marker k (1-based) engages at (k + 1) * step
  double rest_offset_deg = 20.0;  // rest = engage - rest_offset
  double write_offset_deg = 10.0; // write = rest - write_offset (pen on the wall)
};

struct EraseSetup {
  double disc_diameter_mm = 0.0;     // 0 = the machine cannot erase
  slicer::Vec2 offset_mm = slicer::Vec2::Zero();  // disc centre minus marker tip
  double temperature_c = 0.0;
  double dwell_s = 0.0;
  double feed_mm_per_min = 300.0;
};

struct PenSetup {
  PenLift lift = PenLift::Servo;
  int count = 1;                      // pens the machine can hold or be given
  double width_mm = 0.5;              // line width (hatch spacing)
  double capacity_mm = 0.0;           // ink per pen in drawn mm; 0 = not tracked
  bool pause_on_empty = false;        // insert change_gcode when a pen runs dry
  std::vector<std::string> change_gcode;  // manual pen change; {pen} = 1-based number
  int servo_index = 0;
  double up_value = 90.0, down_value = 30.0;  // servo angle (Marlin) or spindle S (GRBL)
  double dwell_s = 0.15;              // after each lift or drop
  double z_up_mm = 2.0, z_down_mm = 0.0;
  DrumAngles drum;
  double draw_feed_mm_per_min = 3000.0;
  EraseSetup erase;
};

struct PlotterSetup {
  PlotterKind kind = PlotterKind::Xy;
  // Polargraph (vPlotter / Scribit): motors (nails) at (0, 0) and (motor_distance, 0).
  double motor_distance_mm = 0.0;
  double gondola_width_mm = 0.0;      // distance between the cable attachments on the gondola
  double pen_offset_mm = 0.0;         // pen below the attachment line
  double min_tension = 0.5, max_tension = 1.5;  // allowed cable tension / gondola weight
  double max_resolution_loss = 2.0;   // pen moves at most this many times one axis step
  slicer::Vec2 home_mm = slicer::Vec2::Zero();  // where the pen starts and returns
  // Polar R-theta (remote drawing robot): pivot, lever to the angle screw, radius origin.
  slicer::Vec2 pivot_mm = slicer::Vec2::Zero();
  double lever_mm = 0.0;
  double origin_radius_mm = 0.0;      // X = origin_radius - radius
  slicer::Vec2 steps_per_mm = slicer::Vec2(80.0, 80.0);  // per axis
};

struct Plotter {
  bool enabled = false;  // the profile has a "plotter" block
  PlotterSetup setup;
  PenSetup pen;
  slicer::Vec2 area_min_mm = slicer::Vec2::Zero();  // paper frame (kinematics min/max x, y)
  slicer::Vec2 area_max_mm = slicer::Vec2::Zero();
};

// Reads j["plotter"] and j["pen"] (already checked by the schema); problems are appended
// in the profile loader's format.
Plotter read_plotter(const nlohmann::json& j, const std::string& origin,
                     std::vector<std::string>& problems);

std::string to_string(PlotterKind k);

}  // namespace strand::machines
