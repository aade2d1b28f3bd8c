// What every printed ink test shares (issue 32): straight beads and the square fiducial marks
// a photo is rectified by, placed at the corners of the test and listed in its report.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "slicer/toolpath.h"

namespace strand::patterns {

// One straight bead from `a` to `b`.
slicer::Stroke straight_bead(const slicer::Vec2& a, const slicer::Vec2& b, double width_mm, double height_mm,
                             slicer::Feature feature = slicer::Feature::Infill);

// A closed square of side `side_mm` centred on `c`, walked counter-clockwise. Closed squares
// rather than crosses: a printed cross would cross itself, which `strand check` refuses, and
// a square's hole tells a mark from a filament in the photo.
slicer::Stroke square_mark(const slicer::Vec2& c, double side_mm, double width_mm, double height_mm);

// The four marks centred on (+-mx, +-my), nozzle wide, appended to `layer` in the order
// (mx, my), (-mx, my), (-mx, -my), (mx, -my); returns the report's "fiducials" (x_mm, y_mm,
// size_mm, shape).
nlohmann::json add_corner_marks(slicer::Layer& layer, double mx_mm, double my_mm, double size_mm,
                                double nozzle_mm, double height_mm);

// The rules the tests share, appended to `problems` in the house format: the layer height in
// [0.5, 1] x nozzle and marks at least 4 nozzles wide.
void check_layer_and_marks(const std::string& test, double nozzle_mm, double layer_height_mm,
                           double fiducial_mm, std::vector<std::string>& problems);

}  // namespace strand::patterns
