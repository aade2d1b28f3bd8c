// The machine-independent toolpath: exact lines and arcs grouped into uninterrupted strokes,
// strokes into layers. What every generator returns; pure data, cheap to copy.
#pragma once

#include <nlohmann/json.hpp>
#include <cstdint>
#include <string>
#include <vector>

#include "slicer/geometry.h"

namespace strand::slicer {

// What a piece of deposit is for; drives speed factors and viewer colours.
enum class Feature : std::uint8_t {
  Infill,    // log-pile filament, hatching
  Wall,      // outline of a solid region
  Ligament,  // straight rib of a lattice
  Node,      // pass around a chiral node
  Grip,      // solid tab of a tensile specimen
  Frame,     // specimen border that closes a lattice strand
  Link,      // sacrificial connection between layers, outside the part
  Pen,       // plotter stroke
};
std::string to_string(Feature f);
// Throws InputError for an unknown name.
Feature feature_from_string(const std::string& name);

enum class SegmentKind { Line, Arc };

// One piece of a stroke. Its start is the previous segment's end (or the stroke's start).
struct Segment {
  SegmentKind kind = SegmentKind::Line;
  Vec2 end_mm = Vec2::Zero();
  Vec2 center_mm = Vec2::Zero();  // arcs only: the circle's centre
  bool ccw = true;                // arcs only: counter-clockwise (G3) when true
  Feature feature = Feature::Infill;

  bool operator==(const Segment&) const = default;
};
Segment line_to(const Vec2& end_mm, Feature feature);
Segment arc_to(const Vec2& end_mm, const Vec2& center_mm, bool ccw, Feature feature);

// One uninterrupted filament (or pen-down stroke): the nozzle never stops depositing.
struct Stroke {
  Vec2 start_mm = Vec2::Zero();
  std::vector<Segment> segments;
  double width_mm = 0.0;   // bead width (DIW) or pen width
  double height_mm = 0.0;  // bead height; 0 for pens
  int tool = 0;            // extruder or pen index
  bool reversible = false; // planner may draw it backwards (plotting)

  bool operator==(const Stroke&) const = default;
  Vec2 end_mm() const { return segments.empty() ? start_mm : segments.back().end_mm; }
};

// A layer: strokes printed in order at height z_mm. A curved layer (later: a surface) keeps
// the same strokes in the surface's own (u, v) frame and names the surface.
struct Layer {
  double z_mm = 0.0;
  double height_mm = 0.0;  // layer thickness (for viewers and volume)
  std::vector<Stroke> strokes;

  bool operator==(const Layer&) const = default;
};

// What a generator returns: layers plus a record of how they were made.
struct Toolpath {
  std::string generator;        // e.g. "scaffold"
  nlohmann::json parameters;    // resolved user parameters, keys as the CLI flags
  nlohmann::json derived;       // derived sizes (footprint, porosity, ...) for headers/reports
  std::vector<Layer> layers;

  bool operator==(const Toolpath&) const = default;
};

// Length of one segment starting at `from`.
double segment_length(const Vec2& from, const Segment& s);
double stroke_length(const Stroke& s);
// Axis-aligned bounds of all strokes (arcs included exactly); {min, max}.
std::pair<Vec2, Vec2> bounds(const Toolpath& t);
// Reverses a stroke in place (arcs flip direction).
Stroke reversed(const Stroke& s);
// Greedy order from `at`: the nearest start (or end, the stroke reversed) next; `at` ends where
// the last stroke ends.
std::vector<Stroke> nearest_first(std::vector<Stroke> strokes, Vec2& at);

nlohmann::json to_json(const Toolpath& t);

}  // namespace strand::slicer

namespace strand::slicer {

// Cross-section of a deposited bead of `width_mm` squashed to `height_mm`: a rectangle with
// semicircular sides (stadium), A = (w - h) h + pi h^2 / 4 for h <= w; an ellipse
// pi w h / 4 when h > w. mm^2.
double bead_area_mm2(double width_mm, double height_mm);

}  // namespace strand::slicer
