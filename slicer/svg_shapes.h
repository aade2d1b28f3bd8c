// Internal to the SVG importer: the basic shapes (rect, circle, ellipse, line, polyline,
// polygon) as exact curves, and the viewBox mapping of a viewport. Not for use outside slicer/.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "slicer/curves.h"

namespace pugi {
class xml_node;
}

namespace strand::slicer {

// x0 y0 x1 y1 ... as straight pieces; closed adds the piece back to the start (polygon).
SubPath polyline_path(const std::vector<double>& v, bool closed);
SubPath ellipse_path(const Vec2& c, double rx, double ry);
// Rect with rounded corners: rx/ry clamp to half the sides.
SubPath rect_path(double x, double y, double w, double h, double rx, double ry);

// The element's viewBox size; nullopt without one. Throws InputError naming `origin` for a
// viewBox that is not 4 numbers with width and height > 0.
std::optional<Vec2> view_box_size(const pugi::xml_node& n, const std::string& origin);

// viewBox + preserveAspectRatio of `n`: its user space into a viewport of w x h in the
// parent's user space (identity without a viewBox).
Affine viewport_transform(const pugi::xml_node& n, double w, double h, const std::string& origin);

}  // namespace strand::slicer
