// SVG text laid out with Hershey fonts, and the strokes a string should have, computed from
// libhersheyfont's raw glyphs, for the text layout tests (tests only).
#pragma once

#include <string>
#include <vector>

#include "slicer/text_layout.h"

namespace strand::testing {

// `body` inside an <svg> of 200 x 100 mm with a viewBox of 200 x 100 user units (1 mm each).
std::string svg_doc(const std::string& body);

// `body` imported and laid out in the Hershey font `font`.
slicer::TextDrawing hershey_text(const std::string& body,
                                 const std::string& font = "hershey:futural");

// Every vertex of the layout, in order.
std::vector<slicer::Vec2> text_vertices(const slicer::TextDrawing& t);

// The same string laid out by hand from libhersheyfont's raw glyphs: pen at (x0, y0) in
// mm, size in mm, SVG y down.
std::vector<slicer::Vec2> hershey_expected(const std::string& s, const char* font, double x0,
                                           double y0, double size);

// The points pairwise within 0.01 mm (a GoogleTest failure otherwise).
void expect_same_points(const std::vector<slicer::Vec2>& got,
                        const std::vector<slicer::Vec2>& want);

// The advance of `s` in the Hershey font `font` at `size`, mm.
double hershey_width(const std::string& s, const char* font, double size);

}  // namespace strand::testing
