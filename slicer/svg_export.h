// Writing shapes back out as a small standalone SVG document in millimetres (the output of
// `strand text` and `strand trace`), readable again by the importer and by Inkscape.
#pragma once

#include <string>
#include <vector>

#include "slicer/svg_import.h"

namespace strand::slicer {

// One Inkscape layer: a <g> with an id (pens m1..m9 follow from it) and a label.
struct SvgLayer {
  std::string id;
  std::string label;
  std::vector<SvgShape> shapes;
};

// The page is the shapes' bounding box grown by margin_mm on every side; coordinates are
// those of the shapes (mm, y down), written exactly (lines and cubics) with 3 decimals.
// Stroked shapes get stroke_width_mm. Deterministic: same shapes, same bytes.
std::string write_svg(const std::vector<SvgLayer>& layers, double margin_mm, double stroke_width_mm);
// The same on a fixed page from (0, 0) to page_mm (a traced image keeps its frame).
std::string write_svg_page(const std::vector<SvgLayer>& layers, const Vec2& page_mm, double stroke_width_mm);

// Path data ("M 1 2 L 3 4 C ... Z") of sub-paths; arcs are written as lines within 1 µm.
std::string path_data(const std::vector<SubPath>& paths);

}  // namespace strand::slicer
