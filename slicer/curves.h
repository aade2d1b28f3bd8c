// Exact 2D curves as drawn in vector graphics (lines, cubic Béziers, elliptical arcs), their
// affine transforms, and flattening into polylines with a proven distance bound.
#pragma once

#include <Eigen/Core>
#include <utility>
#include <vector>

#include "slicer/geometry.h"

namespace strand::slicer {

// x' = linear * x + offset (SVG's matrix(a b c d e f) is linear = [a c; b d], offset = (e, f)).
struct Affine {
  Eigen::Matrix2d linear = Eigen::Matrix2d::Identity();
  Vec2 offset = Vec2::Zero();

  Vec2 apply(const Vec2& p) const { return linear * p + offset; }
  bool operator==(const Affine&) const = default;
};
// a then b: (b ∘ a)(p) = b(a(p)).
Affine compose(const Affine& b, const Affine& a);

enum class CurveKind {
  Line,   // to p[0]
  Cubic,  // control p[0], p[1], end p[2]
  Arc,    // centre + axes * (cos t, sin t) for t from t0_rad over sweep_rad
};

// One piece of a sub-path; its start is the previous piece's end (or the sub-path start).
struct CurvePiece {
  CurveKind kind = CurveKind::Line;
  Vec2 p[3] = {Vec2::Zero(), Vec2::Zero(), Vec2::Zero()};
  Vec2 center = Vec2::Zero();                       // Arc only
  Eigen::Matrix2d axes = Eigen::Matrix2d::Identity(); // Arc only: columns = the two semi-axes
  double t0_rad = 0.0;                              // Arc only
  double sweep_rad = 0.0;                           // Arc only, signed

  Vec2 end() const;
  bool operator==(const CurvePiece&) const = default;
};

struct SubPath {
  Vec2 start = Vec2::Zero();
  std::vector<CurvePiece> pieces;
  bool closed = false;  // ended by Z (the last piece returns to start)
  bool operator==(const SubPath&) const = default;
};

using Polyline = std::vector<Vec2>;

// Drawings live within this distance of their origin (10 km): a coordinate beyond it, after
// every transform, is refused as absurd before any curve is flattened, mm.
inline constexpr double kMaxCoordinateMm = 1e7;

SubPath transformed(const SubPath& s, const Affine& m);
// Point of an arc piece at parameter t (radians).
Vec2 arc_point(const CurvePiece& arc, double t_rad);
// Point of a cubic from `from` at u in [0, 1].
Vec2 cubic_point(const Vec2& from, const CurvePiece& c, double u);

// Polyline whose every point is within tolerance_mm of the curve and, the bound that matters
// for drawing, every point of the curve within tolerance_mm of the polyline:
// cubics are split (de Casteljau) until both inner control points lie within the tolerance
// of the chord (the curve stays in its control hull, so it stays within the tolerance);
// arcs use n equal steps with sigma_max(axes) * (1 - cos(step / 2)) <= tolerance (the sagitta
// of a unit circle step, stretched at most by the largest singular value of the axes).
Polyline flatten(const SubPath& s, double tolerance_mm);

// Upper bound on the points flatten(s, tolerance_mm) returns, from the control points alone
// (no flattening): a cubic whose largest second difference of control points is D needs at
// most 2^ceil(log4(D / tolerance)) pieces, since each split quarters D and a piece stops once
// its inner control points, within D of the chord, are within the tolerance.
double flatten_point_bound(const SubPath& s, double tolerance_mm);

// Exact axis-aligned bounds {min, max} of the curve (cubic and arc extrema solved, not
// sampled).
std::pair<Vec2, Vec2> curve_bounds(const SubPath& s);

// The largest |x| or |y| of the sub-path's control points (arcs: centre plus semi-axes);
// infinite when any number is not finite.
double max_abs_coordinate(const SubPath& s);

}  // namespace strand::slicer
