// Hatch and concentric fills with Clipper 6: open hatch lines intersected with the filled
// region, or the region offset inwards ring by ring.
#include "postprocess/plot/fill.h"

#include <algorithm>
#include <clipper.hpp>
#include <cmath>

#include "slicer/input_error.h"
#include "slicer/params.h"
#include "slicer/units.h"

namespace strand::post {

namespace {

// Clipper works on integers: 1 unit = 0.1 µm.
constexpr double kUnitsPerMm = 1e4;
// Rounded corners of concentric rings deviate at most this much from true arcs, mm.
constexpr double kRingArcToleranceMm = 0.005;
// Ring vertices closer than this to the chord of their neighbours are dropped before the
// next offset; errors add up over the rings (100 rings: at most 0.1 mm), mm.
constexpr double kRingCleanMm = 0.001;

// Clipper throws on coordinates past its range (about 4.6e14 mm at this scale) and llround
// is undefined past 9.2e14 mm: far-off points are refused first.
ClipperLib::IntPoint to_int(const slicer::Vec2& p) {
  if (!(std::abs(p.x()) <= slicer::kMaxCoordinateMm) ||
      !(std::abs(p.y()) <= slicer::kMaxCoordinateMm)) {
    throw InputError("fill: a point is " + slicer::short_number(p.cwiseAbs().maxCoeff()) +
                     " mm from the origin (at most " +
                     slicer::short_number(slicer::kMaxCoordinateMm) + " mm)");
  }
  return {static_cast<ClipperLib::cInt>(std::llround(p.x() * kUnitsPerMm)),
          static_cast<ClipperLib::cInt>(std::llround(p.y() * kUnitsPerMm))};
}

slicer::Vec2 to_mm(const ClipperLib::IntPoint& p) {
  return slicer::Vec2(static_cast<double>(p.X) / kUnitsPerMm, static_cast<double>(p.Y) / kUnitsPerMm);
}

ClipperLib::Paths to_paths(const std::vector<slicer::Polyline>& outlines) {
  ClipperLib::Paths region;
  for (const auto& o : outlines) {
    ClipperLib::Path path;
    for (const auto& p : o) path.push_back(to_int(p));
    if (path.size() >= 3) region.push_back(path);
  }
  return region;
}

// Bounds of the outlines in a frame rotated by angle_rad: {min, max} of (along, across).
std::pair<slicer::Vec2, slicer::Vec2> frame_bounds(const std::vector<slicer::Polyline>& outlines,
                                                   double angle_rad) {
  const slicer::Vec2 dir(std::cos(angle_rad), std::sin(angle_rad));
  const slicer::Vec2 normal(-dir.y(), dir.x());
  slicer::Vec2 lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
  for (const auto& o : outlines) {
    for (const auto& p : o) {
      const slicer::Vec2 r(p.dot(dir), p.dot(normal));
      lo = lo.cwiseMin(r);
      hi = hi.cwiseMax(r);
    }
  }
  return {lo, hi};
}

void check_line_budget(double extent_mm, double spacing_mm) {
  const double lines = extent_mm / spacing_mm;
  if (lines > kMaxFillLines) {
    throw InputError("plot.hatch-spacing = " + slicer::short_number(spacing_mm) + ": a shape " +
                     slicer::short_number(std::round(extent_mm)) + " mm across would need " +
                     slicer::short_number(std::round(lines)) + " fill lines (at most " +
                     slicer::short_number(kMaxFillLines) + "); use a larger spacing (mm)");
  }
}

slicer::Polyline closed_polyline(const ClipperLib::Path& path) {
  slicer::Polyline pl;
  for (const auto& p : path) pl.push_back(to_mm(p));
  if (!pl.empty()) pl.push_back(pl.front());
  return pl;
}

}  // namespace

FillStyle fill_style_from_string(const std::string& name) {
  if (name == "hatch") return FillStyle::Hatch;
  if (name == "concentric") return FillStyle::Concentric;
  if (name == "outline") return FillStyle::Outline;
  if (name == "none") return FillStyle::None;
  throw InputError("plot.fill = " + name + ": must be one of hatch, concentric, outline, none");
}

std::string to_string(FillStyle s) {
  switch (s) {
    case FillStyle::Hatch: return "hatch";
    case FillStyle::Concentric: return "concentric";
    case FillStyle::Outline: return "outline";
    case FillStyle::None: return "none";
  }
  return "hatch";
}

namespace {

// Clipper's exceptions (a range it cannot represent, an internal failure) become InputErrors.
template <typename F>
auto clipper_call(F f) {
  try {
    return f();
  } catch (const ClipperLib::clipperException& e) {
    throw InputError(std::string("fill: Clipper refused the outline (") + e.what() + ")");
  }
}

std::vector<slicer::Polyline> hatch(const std::vector<slicer::Polyline>& outlines, bool evenodd,
                                    double spacing_mm, double angle_deg) {
  const ClipperLib::Paths region = to_paths(outlines);
  if (region.empty() || !(spacing_mm > 0.0)) return {};
  const double a = slicer::deg_to_rad(angle_deg);
  const slicer::Vec2 dir(std::cos(a), std::sin(a)), normal(-std::sin(a), std::cos(a));
  const auto [lo, hi] = frame_bounds(outlines, a);
  check_line_budget(hi.y() - lo.y(), spacing_mm);
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

std::vector<slicer::Polyline> rings(const std::vector<slicer::Polyline>& outlines, bool evenodd,
                                    double spacing_mm) {
  ClipperLib::Paths region = to_paths(outlines);
  if (region.empty() || !(spacing_mm > 0.0)) return {};
  const auto [lo, hi] = frame_bounds(outlines, 0.0);
  check_line_budget(std::min(hi.x() - lo.x(), hi.y() - lo.y()) / 2, spacing_mm);
  // The fill rule resolved once: simple polygons, outers and holes oppositely oriented.
  ClipperLib::SimplifyPolygons(region, evenodd ? ClipperLib::pftEvenOdd : ClipperLib::pftNonZero);
  std::vector<slicer::Polyline> rings;
  // Ring k offsets ring k-1 by one spacing: erosion by discs composes exactly (eroding by a
  // then b is eroding by a + b). Offsetting the original by k spacings instead costs cubic
  // time in Clipper when a ring collapses exactly at the region's inradius; cleaning each
  // ring first keeps its vertex count in step with its curvature.
  for (;;) {
    ClipperLib::CleanPolygons(region, kRingCleanMm * kUnitsPerMm);
    ClipperLib::ClipperOffset offset;
    offset.ArcTolerance = kRingArcToleranceMm * kUnitsPerMm;
    offset.AddPaths(region, ClipperLib::jtRound, ClipperLib::etClosedPolygon);
    ClipperLib::Paths ring;
    offset.Execute(ring, -spacing_mm * kUnitsPerMm);
    if (ring.empty()) break;
    for (const auto& path : ring) {
      if (path.size() >= 3) rings.push_back(closed_polyline(path));
    }
    region = std::move(ring);
  }
  return rings;
}

}  // namespace

std::vector<slicer::Polyline> hatch_fill(const std::vector<slicer::Polyline>& outlines,
                                         bool evenodd, double spacing_mm, double angle_deg) {
  return clipper_call([&] { return hatch(outlines, evenodd, spacing_mm, angle_deg); });
}

std::vector<slicer::Polyline> concentric_fill(const std::vector<slicer::Polyline>& outlines,
                                              bool evenodd, double spacing_mm) {
  return clipper_call([&] { return rings(outlines, evenodd, spacing_mm); });
}

double fill_point_bound(const std::vector<slicer::Polyline>& outlines, FillStyle style,
                        double spacing_mm, double angle_deg) {
  double vertices = 0.0;
  for (const auto& o : outlines) vertices += static_cast<double>(o.size()) + 1.0;
  if (style == FillStyle::None || outlines.empty()) return 0.0;
  if (style == FillStyle::Outline || !(spacing_mm > 0.0)) return vertices;
  if (style == FillStyle::Concentric) {
    const auto [lo, hi] = frame_bounds(outlines, 0.0);
    const double rings = std::ceil(std::min(hi.x() - lo.x(), hi.y() - lo.y()) / 2 / spacing_mm);
    return vertices + rings * (2.0 * vertices + 64.0);
  }
  const double a = slicer::deg_to_rad(angle_deg);
  const slicer::Vec2 normal(-std::sin(a), std::cos(a));
  double crossings = 0.0;
  for (const auto& o : outlines) {
    for (std::size_t i = 0; i < o.size(); ++i) {
      const double h = std::abs((o[(i + 1) % o.size()] - o[i]).dot(normal));
      crossings += std::floor(h / spacing_mm) + 1.0;
    }
  }
  const auto [lo, hi] = frame_bounds(outlines, a);
  return vertices + crossings + 2.0 * std::ceil((hi.y() - lo.y()) / spacing_mm);
}

std::vector<slicer::Polyline> fill_outline(const std::vector<slicer::Polyline>& outlines) {
  std::vector<slicer::Polyline> out;
  for (auto pl : outlines) {
    if (pl.size() < 2) continue;
    if ((pl.back() - pl.front()).norm() > 0.0) pl.push_back(pl.front());
    out.push_back(std::move(pl));
  }
  return out;
}

}  // namespace strand::post
