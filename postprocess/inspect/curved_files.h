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

// What a rotary file's header says: the axis (machine frame) and the substrate.
struct RotaryHeader {
  slicer::Vec3 axis_dir = slicer::Vec3::UnitX();
  slicer::Vec3 axis_point_mm = slicer::Vec3::Zero();
  double radius_mm = 0.0;
  double length_mm = 0.0;  // 0 when the header does not say
};

// True when the G-code declares a rotary axis (;ROTARY_AXIS: header comment).
bool is_rotary_gcode(std::string_view text);
// Throws InputError naming the file when ;ROTARY_AXIS_DIR:, ;ROTARY_AXIS_POINT: or
// ;SUBSTRATE:cylinder radius= is missing or the axis is not horizontal.
RotaryHeader read_rotary_header(std::string_view text, const std::string& file);
// The moves of a parsed rotary file on the workpiece (deposits and travels).
std::vector<CylinderSample> rotary_samples(const ParsedGcode& parsed, const RotaryHeader& h);

// A curved file back on its workpiece, with the cylinder it lies on. A rotary file names its
// cylinder; a pose CSV does not, so its radius is read from the layers (layer k lies at
// radius + (k + 1) h) and its length from the pattern (centred at mid-length).
struct CurvedPart {
  std::vector<CylinderSample> samples;
  double radius_mm = 0.0;  // 0 when unknown (a one-layer CSV)
  double length_mm = 0.0;
  double bead_width_mm = 0.0;            // rotary ;WIDTH:, or a CSV's layer spacing
  std::vector<double> layer_offsets_mm;  // per layer: deposit radius - cylinder radius
};

// A pose CSV (by its header) or rotary G-code; InputError when the text is neither.
CurvedPart read_curved_part(std::string_view text, const std::string& file);
std::vector<CylinderSample> read_curved_samples(std::string_view text, const std::string& file);

// A workpiece point in the viewing frame of previews: the cylinder axis along x and its u = 0
// line on top (+z), as the nozzle sees it at turn 0 (a rotation: (x, y, z) -> (z, -y, x)).
inline slicer::Vec3 viewing_frame(const slicer::Vec3& p) { return {p.z(), -p.y(), p.x()}; }

}  // namespace strand::post
