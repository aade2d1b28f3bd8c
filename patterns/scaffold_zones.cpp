// Porosity per zone: the bead volume laid inside each zone of the footprint over its volume.
#include "patterns/scaffold_zones.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace strand::patterns {

using slicer::Vec2;

namespace {

// Length of the line c*n + s*u inside the box [lo, hi].
double length_in_box(const Vec2& lo, const Vec2& hi, const Vec2& n, const Vec2& u, double c) {
  double s0 = -std::numeric_limits<double>::infinity(), s1 = -s0;
  const Vec2 base = c * n;
  for (int k = 0; k < 2; ++k) {
    if (std::abs(u[k]) < 1e-12) {
      if (base[k] < lo[k] || base[k] > hi[k]) return 0.0;
      continue;
    }
    double a = (lo[k] - base[k]) / u[k], b = (hi[k] - base[k]) / u[k];
    if (a > b) std::swap(a, b);
    s0 = std::max(s0, a);
    s1 = std::min(s1, b);
  }
  return std::max(0.0, s1 - s0);
}

std::string layer_range(int first, int last) {
  return first == last ? std::to_string(first) : std::to_string(first) + "-" + std::to_string(last);
}

// 1 - the volume laid by layers first..last inside the footprint over their box.
double layers_porosity(const ScaffoldGeometry& g, double layer_height_mm,
                       const std::vector<LaidLayer>& layers, int first, int last) {
  double laid = 0.0;
  for (int k = first; k <= last; ++k) laid += layers[static_cast<std::size_t>(k)].inside_volume_mm3;
  return 1.0 - laid / (g.width_mm * g.depth_mm * layer_height_mm * (last - first + 1));
}

nlohmann::json layer_zones(const ScaffoldParams& p, const ScaffoldGeometry& g,
                           const std::vector<LaidLayer>& layers) {
  const int n = p.grade.zone_count(), count = static_cast<int>(layers.size());
  nlohmann::json out = nlohmann::json::array();
  for (int z = 0; z < n; ++z) {
    // Layer k is in zone min(n - 1, floor(k / count * n)), as GapGrade::at picks its zone.
    int first = count, last = -1;
    for (int k = 0; k < count; ++k) {
      const int zone = std::min(n - 1, static_cast<int>(static_cast<double>(k) / count * n));
      if (zone == z) first = std::min(first, k), last = k;
    }
    if (last < first) continue;
    const double f0 = static_cast<double>(first) / count, f1 = static_cast<double>(last) / count;
    out.push_back({{"layers", layer_range(first, last)},
                   {"from_mm", first * p.layer_height_mm},
                   {"to_mm", (last + 1) * p.layer_height_mm},
                   {"gap_mm", {p.grade.at(f0), p.grade.at(f1)}},
                   {"porosity", layers_porosity(g, p.layer_height_mm, layers, first, last)}});
  }
  return out;
}

}  // namespace

nlohmann::json grade_zones(const ScaffoldParams& p, const ScaffoldGeometry& g,
                           const std::vector<LaidLayer>& layers) {
  if (p.grade.axis == GradeAxis::None || layers.empty()) return nlohmann::json::array();
  if (p.grade.axis == GradeAxis::Z) return layer_zones(p, g, layers);
  const bool x = p.grade.axis == GradeAxis::X;
  const double side = x ? g.width_mm : g.depth_mm, across = x ? g.depth_mm : g.width_mm;
  const double length = x ? p.width_mm : p.depth_mm;  // the graded length, from the low edge
  const int n = p.grade.zone_count();
  nlohmann::json out = nlohmann::json::array();
  for (int z = 0; z < n; ++z) {
    const double from = z * length / n;
    const double to = z + 1 == n ? side : std::min(side, (z + 1) * length / n);
    if (to <= from) continue;
    const int a = x ? 0 : 1;
    Vec2 lo(-g.width_mm / 2, -g.depth_mm / 2), hi(g.width_mm / 2, g.depth_mm / 2);
    lo[a] = from - side / 2;
    hi[a] = to - side / 2;
    double laid = 0.0;
    constexpr int kStrips = 16;
    for (const auto& l : layers) {
      for (const double c : l.offsets) {
        for (int j = 0; j < kStrips; ++j) {
          const double at = c + ((j + 0.5) / kStrips - 0.5) * l.bead_width_mm;
          laid += length_in_box(lo, hi, l.n, l.u, at) * l.bead_area_mm2 / kStrips;
        }
      }
    }
    const double box = (to - from) * across * p.layer_height_mm * static_cast<double>(layers.size());
    out.push_back({{"axis", x ? "x" : "y"},
                   {"from_mm", from},
                   {"to_mm", to},
                   {"gap_mm", p.grade.linear ? nlohmann::json{p.grade.at(from / length), p.grade.at(to / length)}
                                             : nlohmann::json{p.grade.gaps_mm[z], p.grade.gaps_mm[z]}},
                   {"porosity", 1.0 - laid / box}});
  }
  return out;
}

nlohmann::json schedule_zones(const ScaffoldParams& p, const ScaffoldGeometry& g,
                              const std::vector<LaidLayer>& layers) {
  nlohmann::json out = nlohmann::json::array();
  const int count = static_cast<int>(layers.size());
  for (const auto& e : p.schedule) {
    if (e.first >= count) continue;
    const int last = std::min(e.last, count - 1);
    out.push_back({{"layers", layer_range(e.first, last)},
                   {"porosity", layers_porosity(g, p.layer_height_mm, layers, e.first, last)}});
  }
  return out;
}

}  // namespace strand::patterns
