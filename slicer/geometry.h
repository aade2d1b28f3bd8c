// Planar geometry on the core types: segment lengths, arc sampling, intersections.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

namespace strand::slicer {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
// A closed polygon: the last point joins the first, which is not repeated.
using Ring = std::vector<Vec2>;

// z-component of the cross product a × b.
double cross(const Vec2& a, const Vec2& b);
// Angle of p around c in (-pi, pi].
double angle_of(const Vec2& c, const Vec2& p);
// Signed sweep of an arc from `from` to `to` around `center`: positive for ccw, in
// (0, 2pi] for ccw and [-2pi, 0) for cw; a full circle when from == to.
double arc_sweep(const Vec2& center, const Vec2& from, const Vec2& to, bool ccw);
// Unit vector at angle `rad` from the x axis.
Vec2 unit_vector(double rad);
// `v` wrapped into [0, period): angles (period 2 pi) and perimeter parameters.
double wrap_period(double v, double period);
// Point on a circle of `radius` around `center` at angle `rad`.
Vec2 on_circle(const Vec2& center, double radius, double rad);

// How two closed segments p1-p2 and q1-q2 meet.
enum class Contact {
  None,      // disjoint
  Crossing,  // meet at a single point interior to both
  Touch,     // meet at an endpoint of one of them, or overlap collinearly
};
// Classifies the contact of two segments; distances below eps_mm count as contact.
Contact segment_contact(const Vec2& p1, const Vec2& p2, const Vec2& q1, const Vec2& q2,
                        double eps_mm);
// Intersection point of two segments that cross (precondition: segment_contact == Crossing).
Vec2 crossing_point(const Vec2& p1, const Vec2& p2, const Vec2& q1, const Vec2& q2);
// Distance from p to the segment a-b.
double point_segment_distance(const Vec2& p, const Vec2& a, const Vec2& b);

}  // namespace strand::slicer
