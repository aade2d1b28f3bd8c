// Strands per connected part of a region (patterns/region_strands.h).
#include "patterns/region_strands.h"

#include <algorithm>

namespace strand::patterns {

namespace {

// The points a stroke deposits along: its start and every segment's end.
void add_points(const slicer::Stroke& s, std::vector<slicer::Vec2>& out) {
  out.push_back(s.start_mm);
  for (const auto& seg : s.segments) out.push_back(seg.end_mm);
}

}  // namespace

// When every part shrunk by a quarter nozzle is still one part with as many holes, growing it
// back changes no part and no hole (the opening lies inside the region, and a hole of the
// shrunk part holds the region's own): the region stands for its opening, one offset saved.
slicer::Region bead_parts(const slicer::Region& region, double nozzle_mm) {
  const double r = nozzle_mm / 4.0;
  const slicer::Region shrunk = slicer::offset_region(region, -r);
  bool same = shrunk.size() == region.size();
  std::vector<bool> hit(region.size(), false);
  for (std::size_t i = 0; same && i < shrunk.size(); ++i) {
    std::size_t k = 0;
    while (k < region.size() && !slicer::contains({region[k]}, shrunk[i].outer.front())) ++k;
    same = k < region.size() && !hit[k] && shrunk[i].holes.size() == region[k].holes.size();
    if (same) hit[k] = true;
  }
  return same ? region : slicer::offset_region(shrunk, r);
}

// Nine samples are plenty: a strand stays in its region but for the ends of a perimeter
// hugging its boundary.
int part_holding(const slicer::Region& region, const std::vector<slicer::Vec2>& points) {
  constexpr std::size_t kSamples = 9;
  std::vector<slicer::Vec2> samples;
  for (std::size_t i = 0; i < std::min(kSamples, points.size()); ++i) {
    samples.push_back(points.size() <= kSamples ? points[i] : points[i * (points.size() - 1) / (kSamples - 1)]);
  }
  int best = -1, best_count = 0;
  for (std::size_t i = 0; i < region.size(); ++i) {
    const slicer::Region part{region[i]};
    const int count = static_cast<int>(std::count_if(
        samples.begin(), samples.end(), [&](const slicer::Vec2& p) { return slicer::contains(part, p); }));
    if (count > best_count) best = static_cast<int>(i), best_count = count;
  }
  return best;
}

int part_holding(const slicer::Region& region, const slicer::Stroke& stroke) {
  std::vector<slicer::Vec2> points;
  add_points(stroke, points);
  return part_holding(region, points);
}

std::vector<RegionStrands> strands_per_region(const slicer::Region& region,
                                              const std::vector<slicer::Stroke>& strokes) {
  std::vector<RegionStrands> out(region.size());
  for (std::size_t i = 0; i < region.size(); ++i) out[i].holes = static_cast<int>(region[i].holes.size());
  std::vector<slicer::Vec2> points;
  for (std::size_t i = 0; i < strokes.size(); ++i) {
    // A stroke that starts where the previous one ended continues its strand.
    if (i > 0 && strokes[i].start_mm == strokes[i - 1].end_mm()) {
      add_points(strokes[i], points);
      continue;
    }
    if (const int part = part_holding(region, points); part >= 0) ++out[static_cast<std::size_t>(part)].strands;
    points.clear();
    add_points(strokes[i], points);
  }
  if (const int part = part_holding(region, points); part >= 0) ++out[static_cast<std::size_t>(part)].strands;
  return out;
}

int strands_over_bound(const std::vector<RegionStrands>& parts) {
  int over = 0;
  for (const RegionStrands& p : parts) over += std::max(0, p.strands - 1 - p.holes);
  return over;
}

}  // namespace strand::patterns
