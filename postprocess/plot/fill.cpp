// Hatch fills with Clipper 6: open hatch lines intersected with the filled region.
#include "postprocess/plot/fill.h"

#include <clipper.hpp>
#include <cmath>

#include "slicer/units.h"

namespace strand::post {

namespace {

// Clipper works on integers: 1 unit = 0.1 µm.
constexpr double kUnitsPerMm = 1e4;

ClipperLib::IntPoint to_int(const slicer::Vec2& p) {
  return {static_cast<ClipperLib::cInt>(std::llround(p.x() * kUnitsPerMm)),
          static_cast<ClipperLib::cInt>(std::llround(p.y() * kUnitsPerMm))};
}

slicer::Vec2 to_mm(const ClipperLib::IntPoint& p) {
  return slicer::Vec2(static_cast<double>(p.X) / kUnitsPerMm, static_cast<double>(p.Y) / kUnitsPerMm);
}

}  // namespace

std::vector<slicer::Polyline> hatch_fill(const std::vector<slicer::Polyline>& outlines,
                                         bool evenodd, double spacing_mm, double angle_deg) {
  ClipperLib::Paths region;
  slicer::Vec2 lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
  const double a = slicer::deg_to_rad(angle_deg);
  const slicer::Vec2 dir(std::cos(a), std::sin(a)), normal(-std::sin(a), std::cos(a));
  for (const auto& o : outlines) {
    ClipperLib::Path path;
    for (const auto& p : o) {
      path.push_back(to_int(p));
      const slicer::Vec2 r(p.dot(dir), p.dot(normal));  // hatch frame
      lo = lo.cwiseMin(r);
      hi = hi.cwiseMax(r);
    }
    if (path.size() >= 3) region.push_back(path);
  }
  if (region.empty() || !(spacing_mm > 0.0)) return {};
  ClipperLib::Paths lines;
  int k = 0;
  for (double v = lo.y() + spacing_mm / 2; v < hi.y(); v += spacing_mm, ++k) {
    // alternate direction so consecutive lines join with short pen-up moves
    const double u0 = (k % 2 == 0) ? lo.x() - 1.0 : hi.x() + 1.0;
    const double u1 = (k % 2 == 0) ? hi.x() + 1.0 : lo.x() - 1.0;
    lines.push_back({to_int(u0 * dir + v * normal), to_int(u1 * dir + v * normal)});
  }
  ClipperLib::Clipper c;
  c.AddPaths(lines, ClipperLib::ptSubject, false);
  c.AddPaths(region, ClipperLib::ptClip, true);
  ClipperLib::PolyTree tree;
  const auto rule = evenodd ? ClipperLib::pftEvenOdd : ClipperLib::pftNonZero;
  c.Execute(ClipperLib::ctIntersection, tree, ClipperLib::pftNonZero, rule);
  ClipperLib::Paths open;
  ClipperLib::OpenPathsFromPolyTree(tree, open);
  std::vector<slicer::Polyline> out;
  for (const auto& path : open) {
    slicer::Polyline pl;
    for (const auto& p : path) pl.push_back(to_mm(p));
    if (pl.size() >= 2) out.push_back(pl);
  }
  return out;
}

}  // namespace strand::post
