// Regions through Clipper 6: unions from slice contours, offsets, differences.
#include "slicer/region.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <polyclipping/clipper.hpp>

#include "slicer/input_error.h"
#include "slicer/tolerances.h"

namespace strand::slicer {

namespace {

using ClipperLib::IntPoint;
using ClipperLib::Path;
using ClipperLib::Paths;

// Farther than any machine or drawing reaches, and well inside Clipper's integer range
// (4.6e13 mm at kClipperUnitsPerMm): a region past it is refused, never cast.
constexpr double kMaxRegionCoordinateMm = 1e7;

Path to_path(const Ring& ring) {
  Path p;
  p.reserve(ring.size());
  for (const Vec2& v : ring) {
    if (!(std::abs(v.x()) <= kMaxRegionCoordinateMm && std::abs(v.y()) <= kMaxRegionCoordinateMm)) {
      char where[96];
      std::snprintf(where, sizeof where, "(%.6g, %.6g)", v.x(), v.y());
      throw InputError(std::string("region: a contour point at ") + where +
                       " mm lies beyond the 1e+07 mm coordinate range");
    }
    p.emplace_back(static_cast<ClipperLib::cInt>(std::llround(v.x() * kClipperUnitsPerMm)),
                   static_cast<ClipperLib::cInt>(std::llround(v.y() * kClipperUnitsPerMm)));
  }
  return p;
}

Ring to_ring(const Path& p) {
  Ring r;
  r.reserve(p.size());
  for (const IntPoint& q : p) {
    r.emplace_back(static_cast<double>(q.X) / kClipperUnitsPerMm,
                   static_cast<double>(q.Y) / kClipperUnitsPerMm);
  }
  return r;
}

Paths to_paths(const Region& r) {
  Paths out;
  for (const Ring& ring : rings_of(r)) out.push_back(to_path(ring));
  return out;
}

// Outer rings at even depth of the tree, their children holes; islands in holes recurse.
void collect(const ClipperLib::PolyNode& node, Region& out) {
  for (const ClipperLib::PolyNode* outer : node.Childs) {
    RegionPart part;
    part.outer = to_ring(outer->Contour);
    if (signed_area_mm2(part.outer) < 0) std::reverse(part.outer.begin(), part.outer.end());
    for (const ClipperLib::PolyNode* hole : outer->Childs) {
      Ring h = to_ring(hole->Contour);
      if (signed_area_mm2(h) > 0) std::reverse(h.begin(), h.end());
      part.holes.push_back(std::move(h));
      collect(*hole, out);
    }
    out.push_back(std::move(part));
  }
}

Region execute(ClipperLib::Clipper& c, ClipperLib::ClipType type, ClipperLib::PolyFillType fill) {
  ClipperLib::PolyTree tree;
  c.Execute(type, tree, fill, fill);
  Region out;
  collect(tree, out);
  return out;
}

}  // namespace

double signed_area_mm2(const Ring& ring) {
  double a = 0.0;
  for (std::size_t i = 0, n = ring.size(); i < n; ++i) a += cross(ring[i], ring[(i + 1) % n]);
  return a / 2.0;
}

std::vector<Ring> rings_of(const Region& r) {
  std::vector<Ring> out;
  for (const auto& part : r) {
    out.push_back(part.outer);
    out.insert(out.end(), part.holes.begin(), part.holes.end());
  }
  return out;
}

Region region_from_contours(const std::vector<Ring>& contours) {
  Paths paths;
  for (const Ring& ring : contours) paths.push_back(to_path(ring));
  ClipperLib::CleanPolygons(paths, 1.0);  // drop vertices within 1 unit (0.01 um)
  ClipperLib::Clipper c;
  c.AddPaths(paths, ClipperLib::ptSubject, true);
  return execute(c, ClipperLib::ctUnion, ClipperLib::pftEvenOdd);
}

Region region_from_oriented_loops(const std::vector<Ring>& loops) {
  Paths paths;
  for (const Ring& ring : loops) paths.push_back(to_path(ring));
  ClipperLib::CleanPolygons(paths, 1.0);
  ClipperLib::Clipper c;
  c.AddPaths(paths, ClipperLib::ptSubject, true);
  return execute(c, ClipperLib::ctUnion, ClipperLib::pftNonZero);
}

Region offset_region(const Region& r, double delta_mm) {
  ClipperLib::ClipperOffset o(2.0, kOffsetArcToleranceMm * kClipperUnitsPerMm);
  o.AddPaths(to_paths(r), ClipperLib::jtRound, ClipperLib::etClosedPolygon);
  ClipperLib::PolyTree tree;
  o.Execute(tree, delta_mm * kClipperUnitsPerMm);
  Region out;
  collect(tree, out);
  return out;
}

Region region_difference(const Region& a, const Region& b) {
  ClipperLib::Clipper c;
  c.AddPaths(to_paths(a), ClipperLib::ptSubject, true);
  c.AddPaths(to_paths(b), ClipperLib::ptClip, true);
  return execute(c, ClipperLib::ctDifference, ClipperLib::pftNonZero);
}

Region region_intersection(const Region& a, const Region& b) {
  ClipperLib::Clipper c;
  c.AddPaths(to_paths(a), ClipperLib::ptSubject, true);
  c.AddPaths(to_paths(b), ClipperLib::ptClip, true);
  return execute(c, ClipperLib::ctIntersection, ClipperLib::pftNonZero);
}

double area_mm2(const RegionPart& p) {
  double a = signed_area_mm2(p.outer);
  for (const Ring& h : p.holes) a += signed_area_mm2(h);
  return a;
}

double area_mm2(const Region& r) {
  double a = 0.0;
  for (const auto& p : r) a += area_mm2(p);
  return a;
}

bool contains(const Region& r, const Vec2& p) {
  bool inside = false;
  for (const Ring& ring : rings_of(r)) {
    for (std::size_t i = 0, n = ring.size(), j = n - 1; i < n; j = i++) {
      const Vec2& a = ring[i];
      const Vec2& b = ring[j];
      if ((a.y() > p.y()) != (b.y() > p.y()) &&
          p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x()) {
        inside = !inside;
      }
    }
  }
  return inside;
}

std::pair<Vec2, Vec2> region_bounds(const Region& r) {
  bool first = true;
  Vec2 lo = Vec2::Zero(), hi = Vec2::Zero();
  for (const auto& part : r) {
    for (const Vec2& v : part.outer) {
      lo = first ? v : lo.cwiseMin(v);
      hi = first ? v : hi.cwiseMax(v);
      first = false;
    }
  }
  return {lo, hi};
}

}  // namespace strand::slicer
