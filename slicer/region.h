// Planar regions: polygons with holes, as a layer's slice of a part is. Boolean work and
// offsets go through Clipper (integer coordinates, kClipperUnitsPerMm).
#pragma once

#include <vector>

#include "slicer/geometry.h"

namespace strand::slicer {

// One connected piece of a region: an outer ring (counter-clockwise) and its holes
// (clockwise), none touching.
struct RegionPart {
  Ring outer;
  std::vector<Ring> holes;
  bool operator==(const RegionPart&) const = default;
};
using Region = std::vector<RegionPart>;

// The region enclosed by closed contours of any orientation (even-odd nesting: a contour
// inside another is a hole, one inside a hole an island).
Region region_from_contours(const std::vector<Ring>& contours);
// The region where the winding number of oriented loops is not zero (Clipper's nonzero
// union): overlapping loops merge, a loop run clockwise (an inside-out shell) still counts,
// a clockwise loop inside a counter-clockwise one (a cavity) is a hole.
Region region_from_oriented_loops(const std::vector<Ring>& loops);
// Grown (delta > 0) or shrunk (delta < 0) by |delta_mm|, round joins; parts that vanish are
// dropped, parts that pinch apart become separate parts.
Region offset_region(const Region& r, double delta_mm);
// a minus b.
Region region_difference(const Region& a, const Region& b);
// What a and b share.
Region region_intersection(const Region& a, const Region& b);
double area_mm2(const RegionPart& p);
double area_mm2(const Region& r);
// Every ring of the region, outers and holes, with their orientation.
std::vector<Ring> rings_of(const Region& r);
// Signed area of a ring: positive counter-clockwise, mm^2.
double signed_area_mm2(const Ring& ring);
// Even-odd point-in-region test.
bool contains(const Region& r, const Vec2& p);
// Axis-aligned bounds {min, max} of the region (zero when empty).
std::pair<Vec2, Vec2> region_bounds(const Region& r);

}  // namespace strand::slicer
