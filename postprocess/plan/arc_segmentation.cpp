// Chord count from the sagitta bound r (1 - cos(phi / 2)) <= tolerance.
#include "postprocess/plan/arc_segmentation.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "slicer/units.h"

namespace strand::post {

int chords_needed(double radius_mm, double sweep_rad, double tol) {
  assert(tol > 0);
  const double s = std::abs(sweep_rad);
  if (radius_mm <= tol) return std::max(1, static_cast<int>(std::ceil(s / (slicer::kPi / 2))));
  const double max_step = 2.0 * std::acos(1.0 - tol / radius_mm);
  // Never more than a quarter turn per chord, so faceting stays visible as a circle.
  const double step = std::min(max_step, slicer::kPi / 2);
  return std::max(1, static_cast<int>(std::ceil(s / step - 1e-12)));
}

std::vector<Vec2> segment_arc(const Vec2& from, const Vec2& center, const Vec2& to, bool ccw,
                              double tol) {
  const double r = (from - center).norm();
  const double sweep = slicer::arc_sweep(center, from, to, ccw);
  const int n = chords_needed(r, sweep, tol);
  const double a0 = slicer::angle_of(center, from);
  std::vector<Vec2> pts;
  pts.reserve(static_cast<std::size_t>(n));
  for (int i = 1; i < n; ++i) pts.push_back(slicer::on_circle(center, r, a0 + sweep * i / n));
  pts.push_back(to);
  return pts;
}

}  // namespace strand::post
