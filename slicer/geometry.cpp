// Planar geometry helpers on Eigen vectors (mm).
#include "slicer/geometry.h"

#include <algorithm>
#include <cmath>

#include "slicer/units.h"

namespace strand::slicer {

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

double angle_of(const Vec2& c, const Vec2& p) { return std::atan2(p.y() - c.y(), p.x() - c.x()); }

double arc_sweep(const Vec2& center, const Vec2& from, const Vec2& to, bool ccw) {
  double sweep = angle_of(center, to) - angle_of(center, from);
  if (ccw) {
    while (sweep <= 0.0) sweep += kTwoPi;
    while (sweep > kTwoPi) sweep -= kTwoPi;
  } else {
    while (sweep >= 0.0) sweep -= kTwoPi;
    while (sweep < -kTwoPi) sweep += kTwoPi;
  }
  return sweep;
}

Vec2 unit_vector(double rad) { return Vec2(std::cos(rad), std::sin(rad)); }

double wrap_period(double v, double period) {
  // Most calls are already within one period either side: fmod would return v unchanged
  // there, so skip it (the same result, and fmod is slow on the generators' hot paths).
  if (v >= 0 && v < period) return v;
  if (v < 0 && v > -period) return v + period;
  v = std::fmod(v, period);
  return v < 0 ? v + period : v;
}

Vec2 on_circle(const Vec2& center, double radius, double rad) {
  return center + radius * Vec2(std::cos(rad), std::sin(rad));
}

double point_segment_distance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  if (len2 == 0.0) return (p - a).norm();
  const double t = std::clamp((p - a).dot(ab) / len2, 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

namespace {

// Signed distance of p from the line through a-b (positive on the left), mm.
double side(const Vec2& a, const Vec2& b, const Vec2& p) {
  const Vec2 ab = b - a;
  const double len = ab.norm();
  if (len == 0.0) return 0.0;
  return cross(ab, p - a) / len;
}

int sign_eps(double v, double eps) { return v > eps ? 1 : (v < -eps ? -1 : 0); }

}  // namespace

Contact segment_contact(const Vec2& p1, const Vec2& p2, const Vec2& q1, const Vec2& q2,
                        double eps_mm) {
  const int o1 = sign_eps(side(p1, p2, q1), eps_mm);
  const int o2 = sign_eps(side(p1, p2, q2), eps_mm);
  const int o3 = sign_eps(side(q1, q2, p1), eps_mm);
  const int o4 = sign_eps(side(q1, q2, p2), eps_mm);
  if (o1 * o2 < 0 && o3 * o4 < 0) return Contact::Crossing;
  if (point_segment_distance(q1, p1, p2) <= eps_mm || point_segment_distance(q2, p1, p2) <= eps_mm ||
      point_segment_distance(p1, q1, q2) <= eps_mm || point_segment_distance(p2, q1, q2) <= eps_mm) {
    return Contact::Touch;
  }
  return Contact::None;
}

Vec2 crossing_point(const Vec2& p1, const Vec2& p2, const Vec2& q1, const Vec2& q2) {
  const Vec2 r = p2 - p1;
  const Vec2 s = q2 - q1;
  const double denom = cross(r, s);
  const double t = denom == 0.0 ? 0.0 : cross(q1 - p1, s) / denom;
  return p1 + t * r;
}

}  // namespace strand::slicer
