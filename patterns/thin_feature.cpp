// Thin features: the strips the fill cannot reach, their centre lines (slicer/medial_axis.h),
// stretched to free ends, trimmed clear of the fill, as beads.
#include "patterns/thin_feature.h"

#include "patterns/region_clip.h"
#include "slicer/medial_axis.h"

namespace strand::patterns {

using slicer::Region;
using slicer::Vec2;

namespace {

// Strips of a part smaller than this (in nozzle^2) hold no bead a nozzle long at half a
// bead wide: the corners a bead does not reach, skipped before any diagram is built.
constexpr double kMinStripAreaNozzle2 = 0.5;

// Where centre lines are looked for: strips of a part that no bead centred d/2 inside reaches,
// and a whole part no disc of diameter 2 d fits in (a free-standing rib, a small island),
// which the fill would otherwise trace with a loop folded on itself.
struct ThinPlace {
  Region region;
  bool whole_part = false;
};

std::vector<ThinPlace> thin_places(const Region& layer, double d) {
  std::vector<ThinPlace> out;
  for (const slicer::RegionPart& part : layer) {
    const Region one{part};
    if (slicer::offset_region(one, -d).empty()) {
      out.push_back({one, true});
      continue;
    }
    const Region reached = slicer::offset_region(slicer::offset_region(one, -d / 2.0), d / 2.0);
    for (slicer::RegionPart& strip : slicer::region_difference(one, reached)) {
      if (slicer::area_mm2(strip) >= kMinStripAreaNozzle2 * d * d) out.push_back({{std::move(strip)}, false});
    }
  }
  return out;
}

// A free end (not a fork, where another line goes on) stretched along its last segment until
// a bead of width d reaches the feature's end: the axis stops w/2 short of it.
void stretch_ends(slicer::CentreLine& line, const std::vector<slicer::CentreLine>& all, double d) {
  const bool closed = line.points.size() > 2 && line.points.front() == line.points.back();
  if (closed) return;
  auto on_other = [&](const Vec2& p) {
    for (const auto& other : all) {
      if (&other == &line) continue;
      for (const Vec2& q : other.points) if (q == p) return true;
    }
    return false;
  };
  for (const bool front : {true, false}) {
    const std::size_t n = line.points.size();
    const Vec2 end = front ? line.points[0] : line.points[n - 1];
    const Vec2 prev = front ? line.points[1] : line.points[n - 2];
    const double reach = (front ? line.width_mm[0] : line.width_mm[n - 1]) / 2.0 - d / 2.0;
    if (reach <= 0.0 || on_other(end) || (end - prev).norm() == 0.0) continue;
    (front ? line.points[0] : line.points[n - 1]) = end + (end - prev).normalized() * reach;
  }
}

// The band within `radius_mm` of the lines: each segment as a sliver, grown.
Region footprint(const std::vector<slicer::CentreLine>& lines, double radius_mm) {
  constexpr double kSliverMm = 1e-3;
  std::vector<slicer::Ring> slivers;
  for (const auto& line : lines) {
    for (std::size_t i = 0; i + 1 < line.points.size(); ++i) {
      const Vec2 a = line.points[i], b = line.points[i + 1];
      if ((b - a).norm() == 0.0) continue;
      const Vec2 n = Vec2(a.y() - b.y(), b.x() - a.x()).normalized() * kSliverMm;
      slivers.push_back({a - n, b - n, b + n, a + n});
    }
  }
  return slicer::offset_region(slicer::region_from_oriented_loops(slivers), radius_mm - kSliverMm);
}

// The parts of `lines` inside `keep`, a closed line cut open joined again across its start.
std::vector<std::vector<Vec2>> clipped(const std::vector<slicer::CentreLine>& lines,
                                       const Region& keep) {
  const RingSet rs = ring_set(slicer::rings_of(keep));
  std::vector<std::vector<Vec2>> out;
  for (const auto& line : lines) {
    PatternLine pl{line.points, std::vector<slicer::Feature>(line.points.size() - 1, slicer::Feature::Wall), 0};
    std::vector<FillPiece> pieces = clip_to_rings(rs, {pl});
    const bool closed = line.points.front() == line.points.back();
    if (closed && pieces.size() > 1 && pieces.front().start.ring < 0 && pieces.back().end.ring < 0) {
      auto& last = pieces.back().line.points;
      last.insert(last.end(), pieces.front().line.points.begin() + 1, pieces.front().line.points.end());
      pieces.erase(pieces.begin());
    }
    for (auto& p : pieces) out.push_back(std::move(p.line.points));
  }
  return out;
}

slicer::Stroke bead(const std::vector<Vec2>& points, double width, double height) {
  slicer::Stroke s;
  s.start_mm = points.front();
  for (std::size_t i = 1; i < points.size(); ++i) s.segments.push_back(slicer::line_to(points[i], slicer::Feature::Wall));
  s.width_mm = width;
  s.height_mm = height;
  return s;
}

// True when the polyline crosses any of `beads` (a touch is allowed: beads may meet at a fork
// or side by side). Beads of neighbouring thin places, or a free end stretched towards another
// line, could otherwise cross.
bool crosses_any(const std::vector<Vec2>& points, const std::vector<slicer::Stroke>& beads) {
  Vec2 lo = points.front(), hi = points.front();
  for (const Vec2& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  for (const slicer::Stroke& b : beads) {
    std::vector<Vec2> q{b.start_mm};
    for (const auto& seg : b.segments) q.push_back(seg.end_mm);
    Vec2 blo = q.front(), bhi = q.front();
    for (const Vec2& p : q) blo = blo.cwiseMin(p), bhi = bhi.cwiseMax(p);
    if ((blo.array() > hi.array()).any() || (bhi.array() < lo.array()).any()) continue;
    for (std::size_t i = 0; i + 1 < points.size(); ++i)
      for (std::size_t j = 0; j + 1 < q.size(); ++j)
        if (slicer::segment_contact(points[i], points[i + 1], q[j], q[j + 1], 1e-9) ==
            slicer::Contact::Crossing)
          return true;
  }
  return false;
}

}  // namespace

ThinFeatures thin_features(const Region& layer, double nozzle_mm, double layer_height_mm) {
  const double d = nozzle_mm;
  ThinFeatures out;
  out.fill_region = layer;
  const slicer::MedialAxisLimits limits{d / 2.0, 2.0 * d, d};
  struct Found {
    Region place;
    bool whole_part = false;  // the fill leaves it entirely to its beads
    std::vector<slicer::CentreLine> lines;
  };
  std::vector<Found> found;
  Region whole;
  for (ThinPlace& place : thin_places(layer, d)) {
    std::vector<slicer::CentreLine> lines = slicer::centre_lines(place.region, limits);
    if (lines.empty()) continue;
    for (auto& line : lines) stretch_ends(line, lines, d);
    if (place.whole_part) whole.insert(whole.end(), place.region.begin(), place.region.end());
    found.push_back({std::move(place.region), place.whole_part, std::move(lines)});
  }
  if (found.empty()) return out;
  // Fill beads are centred within offset(fill, -d/2) (a strip no bead reaches does not change
  // it): a centre line d from there touches them at most.
  const Region fill = slicer::region_difference(layer, whole);
  const Region near_fill = slicer::offset_region(slicer::offset_region(fill, -d / 2.0), d);
  const Region keep = slicer::region_difference(slicer::offset_region(layer, d), near_fill);
  Region covered = whole;
  for (const Found& f : found) {
    std::vector<slicer::CentreLine> kept;
    for (auto& points : clipped(f.lines, keep)) {
      const double len = slicer::polyline_length_mm(points);
      if (len < d || crosses_any(points, out.beads)) continue;
      out.beads.push_back(bead(points, d, layer_height_mm));
      out.length_mm += len;
      kept.push_back({std::move(points), {}});
    }
    // The bead prints the strip where it lies; a part of the strip too narrow for it stays
    // in the fill region, where the wall check lists it as skipped.
    if (f.whole_part || kept.empty()) continue;
    for (auto& part : slicer::region_intersection(f.place, footprint(kept, d))) covered.push_back(std::move(part));
  }
  out.fill_region = slicer::region_difference(layer, covered);
  return out;
}

PartThinBeads print_thin_features(std::vector<Region>& layers, double nozzle_mm,
                                  double layer_height_mm) {
  PartThinBeads out;
  out.per_layer.resize(layers.size());
  for (std::size_t k = 0; k < layers.size(); ++k) {
    ThinFeatures t = thin_features(layers[k], nozzle_mm, layer_height_mm);
    if (t.beads.empty()) continue;
    layers[k] = std::move(t.fill_region);
    out.count += static_cast<int>(t.beads.size());
    out.length_mm += t.length_mm;
    out.per_layer[k] = std::move(t.beads);
  }
  return out;
}

}  // namespace strand::patterns
