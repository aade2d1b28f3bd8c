// The thin-wall skip (jobs/slice_thin_walls.h).
#include "jobs/slice_thin_walls.h"

#include <tbb/parallel_for.h>

#include <cmath>
#include <cstdio>

#include "slicer/params.h"

namespace strand::jobs {

namespace {

std::string mm_text(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3f", v);
  return buf;
}

}  // namespace

std::vector<std::string> skip_thin_walls(std::vector<slicer::Region>& layers,
                                         const patterns::RegionPattern& p,
                                         nlohmann::json& skipped) {
  const double d = p.nozzle_mm, r = d / 2.0, h = p.layer_height_mm;
  // Each layer's strips on its own (in the caller's task arena, on every thread there): layer
  // k's reads layers k - 1 to k + 1, none of which changes until all are found.
  std::vector<slicer::Region> lost(layers.size());
  tbb::parallel_for(std::size_t{0}, layers.size(), [&](std::size_t k) {
    const slicer::Region reached = slicer::offset_region(slicer::offset_region(layers[k], -r), r);
    for (const auto& piece : slicer::region_difference(layers[k], reached)) {
      const double area = slicer::area_mm2(piece);
      if (area <= 4.0 * d * d) continue;
      bool wall = true;
      for (const std::size_t j : {k - 1, k + 1}) {  // k - 1 wraps for k = 0: not a layer
        wall = wall && j < layers.size() &&
               slicer::area_mm2(slicer::region_intersection({piece}, layers[j])) > area / 2;
      }
      if (wall) lost[k].push_back(piece);
    }
  });
  std::vector<std::string> notes;
  for (std::size_t k = 0; k < layers.size();) {
    if (lost[k].empty()) {
      ++k;
      continue;
    }
    std::size_t end = k;
    double area = 0.0;
    slicer::Region first = lost[k];
    for (; end < layers.size() && !lost[end].empty(); ++end) {
      area += slicer::area_mm2(lost[end]);
      layers[end] = slicer::region_difference(layers[end], lost[end]);
    }
    const auto [lo, hi] = slicer::region_bounds(first);
    const slicer::Vec2 c = (lo + hi) / 2.0;
    const double z0 = static_cast<double>(k) * h, z1 = static_cast<double>(end) * h;
    notes.push_back("skipped " + mm_text(area) + " mm2 too thin for the " +
                    slicer::short_number(d) + " mm nozzle near (" + mm_text(c.x()) + ", " +
                    mm_text(c.y()) + "), z " + mm_text(z0) + " to " + mm_text(z1) + " mm");
    skipped.push_back(
        {{"area_mm2", std::round(area * 1000.0) / 1000.0},
         {"near_mm", {std::round(c.x() * 1000.0) / 1000.0, std::round(c.y() * 1000.0) / 1000.0}},
         {"z_mm", {std::round(z0 * 1000.0) / 1000.0, std::round(z1 * 1000.0) / 1000.0}}});
    k = end;
  }
  return notes;
}

}  // namespace strand::jobs
