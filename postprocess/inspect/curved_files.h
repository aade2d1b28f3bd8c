// Curved-substrate files read back onto their workpiece: a pose CSV's contact points, or a
// rotary G-code's nozzle positions turned back by A about the axis its header names. Both
// checks and previews start here.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "postprocess/inspect/gcode_parser.h"
#include "slicer/motion.h"

namespace strand::post {

// One position on the workpiece (frame: cylinder axis = z, u = 0 on +x).
struct CylinderSample {
  int layer = 0;
  bool extrude = false;  // the motion from the previous sample deposits
  slicer::Vec3 p_mm = slicer::Vec3::Zero();
  std::size_t source = 0;  // CSV row or G-code line
  slicer::Feature feature = slicer::Feature::Infill;
};

// What a rotary file's header says: the axis (machine frame) and the substrate radius.
struct RotaryHeader {
  slicer::Vec3 axis_dir = slicer::Vec3::UnitX();
  slicer::Vec3 axis_point_mm = slicer::Vec3::Zero();
  double radius_mm = 0.0;
};

// True when the G-code declares a rotary axis (;ROTARY_AXIS: header comment).
bool is_rotary_gcode(std::string_view text);
// Throws InputError naming the file when ;ROTARY_AXIS_DIR:, ;ROTARY_AXIS_POINT: or
// ;SUBSTRATE:cylinder radius= is missing or the axis is not horizontal.
RotaryHeader read_rotary_header(std::string_view text, const std::string& file);
// The moves of a parsed rotary file on the workpiece (deposits and travels).
std::vector<CylinderSample> rotary_samples(const ParsedGcode& parsed, const RotaryHeader& h);

// A pose CSV (by its header) or rotary G-code as samples on the workpiece; InputError when
// the text is neither.
std::vector<CylinderSample> read_curved_samples(std::string_view text, const std::string& file);

// The samples as a program in a viewing frame: the cylinder axis along x and its u = 0 line
// on top (+z), as the nozzle sees it at turn 0; one layer per sample layer.
slicer::MotionProgram workpiece_program(const std::vector<CylinderSample>& samples);

}  // namespace strand::post
