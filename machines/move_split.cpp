// Splitting lines and arcs at fractions of their length.
#include "machines/move_split.h"

#include <cmath>

namespace strand::machines {

using slicer::Vec2;
using slicer::Vec3;

double path_length(const Vec3& from, const slicer::Move& mv) {
  if (!mv.is_arc) return (mv.end_mm - from).norm();
  const Vec2 a = from.head<2>();
  const double r = (a - mv.center_mm).norm();
  const double xy = r * std::abs(slicer::arc_sweep(mv.center_mm, a, mv.end_mm.head<2>(), mv.ccw));
  return std::hypot(xy, mv.end_mm.z() - from.z());
}

Vec3 point_along(const Vec3& from, const slicer::Move& mv, double t) {
  if (!mv.is_arc) return from + t * (mv.end_mm - from);
  const Vec2 a = from.head<2>();
  const double r = (a - mv.center_mm).norm();
  const double sweep = slicer::arc_sweep(mv.center_mm, a, mv.end_mm.head<2>(), mv.ccw);
  const Vec2 p = slicer::on_circle(mv.center_mm, r, slicer::angle_of(mv.center_mm, a) + t * sweep);
  return Vec3(p.x(), p.y(), from.z() + t * (mv.end_mm.z() - from.z()));
}

std::vector<slicer::Move> split_move(const Vec3& from, const slicer::Move& mv,
                                     const std::vector<double>& cuts) {
  std::vector<slicer::Move> out;
  double last_t = 0.0;
  for (std::size_t i = 0; i <= cuts.size(); ++i) {
    const double t = i < cuts.size() ? cuts[i] : 1.0;
    slicer::Move piece = mv;
    piece.end_mm = i < cuts.size() ? point_along(from, mv, t) : mv.end_mm;
    piece.volume_mm3 = mv.volume_mm3 * (t - last_t);
    out.push_back(piece);
    last_t = t;
  }
  return out;
}

}  // namespace strand::machines
