// Curve evaluation, transforms and bounded-error flattening.
#include "slicer/curves.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

#include "slicer/units.h"

namespace strand::slicer {

namespace {

// Deepest de Casteljau split: 2^-40 of a curve is far below any pen's resolution.
constexpr int kMaxSplitDepth = 40;
// An arc is never cut into more steps than this (a 100 m circle at 1 µm stays well below).
constexpr int kMaxArcSteps = 1 << 20;

struct Cubic {
  Vec2 a, b, c, d;
};

// Splits a cubic needs: each de Casteljau split quarters the largest second difference D of
// the control points, and both inner control points lie within D of the chord, so after
// ceil(log4(D / tol)) splits every piece is within the tolerance (capped at kMaxSplitDepth;
// a NaN gives 0).
int cubic_depth(const Cubic& q, double tol) {
  const double d = std::max((q.a - 2 * q.b + q.c).norm(), (q.b - 2 * q.c + q.d).norm());
  if (!(d > tol)) return 0;
  const double depth = std::ceil(std::log(d / tol) / std::log(4.0));
  return depth < kMaxSplitDepth ? static_cast<int>(depth) : kMaxSplitDepth;
}

// Splits while a control point is off the chord by more than tol, never deeper than
// `depth_left` (the proven bound above), so the points are at most 2^cubic_depth.
void flatten_cubic(const Cubic& q, double tol, int depth_left, Polyline& out) {
  const double err = std::max(point_segment_distance(q.b, q.a, q.d),
                              point_segment_distance(q.c, q.a, q.d));
  if (!(err > tol) || depth_left <= 0) {
    out.push_back(q.d);
    return;
  }
  const Vec2 ab = (q.a + q.b) / 2, bc = (q.b + q.c) / 2, cd = (q.c + q.d) / 2;
  const Vec2 abc = (ab + bc) / 2, bcd = (bc + cd) / 2, mid = (abc + bcd) / 2;
  flatten_cubic({q.a, ab, abc, mid}, tol, depth_left - 1, out);
  flatten_cubic({mid, bcd, cd, q.d}, tol, depth_left - 1, out);
}

// Equal steps of an arc: sigma_max(axes) * (1 - cos(step / 2)) <= tol, 1..kMaxArcSteps.
int arc_steps(const CurvePiece& arc, double tol) {
  const double sigma = Eigen::JacobiSVD<Eigen::Matrix2d>(arc.axes).singularValues()(0);
  if (!(sigma > tol)) return 1;
  // 1 - cos(step / 2) <= tol / sigma  <=>  step <= 2 acos(1 - tol / sigma)
  const double step = 2.0 * std::acos(std::max(-1.0, 1.0 - tol / sigma));
  const double n = std::ceil(std::abs(arc.sweep_rad) / step);
  if (!(n < kMaxArcSteps)) return kMaxArcSteps;  // also a zero step or a NaN
  return std::max(1, static_cast<int>(n));
}

void flatten_arc(const CurvePiece& arc, double tol, Polyline& out) {
  const int n = arc_steps(arc, tol);
  for (int i = 1; i <= n; ++i) out.push_back(arc_point(arc, arc.t0_rad + arc.sweep_rad * i / n));
}

void extend(std::pair<Vec2, Vec2>& box, const Vec2& p) {
  box.first = box.first.cwiseMin(p);
  box.second = box.second.cwiseMax(p);
}

// Interior extrema of a cubic: roots in (0, 1) of its derivative, per axis.
void cubic_extrema(const Cubic& q, std::pair<Vec2, Vec2>& box) {
  const Vec2 a = -q.a + 3 * q.b - 3 * q.c + q.d, b = 2 * (q.a - 2 * q.b + q.c), c = q.b - q.a;
  const CurvePiece piece{CurveKind::Cubic, {q.b, q.c, q.d}};
  for (int i = 0; i < 2; ++i) {
    double roots[2];
    int n = 0;
    if (std::abs(a[i]) < 1e-12 * (std::abs(b[i]) + std::abs(c[i]))) {
      if (b[i] != 0.0) roots[n++] = -c[i] / b[i];
    } else {
      const double disc = b[i] * b[i] - 4 * a[i] * c[i];
      if (disc >= 0) {
        roots[n++] = (-b[i] + std::sqrt(disc)) / (2 * a[i]);
        roots[n++] = (-b[i] - std::sqrt(disc)) / (2 * a[i]);
      }
    }
    for (int k = 0; k < n; ++k) {
      if (roots[k] > 0 && roots[k] < 1) extend(box, cubic_point(q.a, piece, roots[k]));
    }
  }
}

// Interior extrema of an arc: x(t) = cx + A00 cos t + A01 sin t peaks at atan2(A01, A00)
// and half a turn on; each such angle inside the sweep counts.
void arc_extrema(const CurvePiece& arc, std::pair<Vec2, Vec2>& box) {
  const double lo = std::min(arc.t0_rad, arc.t0_rad + arc.sweep_rad);
  const double hi = lo + std::min(std::abs(arc.sweep_rad), kTwoPi);  // a full turn has them all
  for (int i = 0; i < 2; ++i) {
    const double peak = std::atan2(arc.axes(i, 1), arc.axes(i, 0));
    for (double t = peak + kPi * std::ceil((lo - peak) / kPi); t < hi; t += kPi) {
      extend(box, arc_point(arc, t));
    }
  }
}

void take_abs(double v, double& m) { m = std::isnan(v) ? INFINITY : std::max(m, std::abs(v)); }

}  // namespace

Affine compose(const Affine& b, const Affine& a) {
  return {b.linear * a.linear, b.linear * a.offset + b.offset};
}

Vec2 CurvePiece::end() const {
  switch (kind) {
    case CurveKind::Line: return p[0];
    case CurveKind::Cubic: return p[2];
    case CurveKind::Arc: return arc_point(*this, t0_rad + sweep_rad);
  }
  return p[0];
}

Vec2 arc_point(const CurvePiece& arc, double t_rad) {
  return arc.center + arc.axes * Vec2(std::cos(t_rad), std::sin(t_rad));
}

Vec2 cubic_point(const Vec2& from, const CurvePiece& c, double u) {
  const double v = 1.0 - u;
  return v * v * v * from + 3 * v * v * u * c.p[0] + 3 * v * u * u * c.p[1] + u * u * u * c.p[2];
}

SubPath transformed(const SubPath& s, const Affine& m) {
  SubPath out = s;
  out.start = m.apply(s.start);
  for (auto& piece : out.pieces) {
    for (auto& q : piece.p) q = m.apply(q);
    if (piece.kind == CurveKind::Arc) {
      piece.center = m.apply(piece.center);
      piece.axes = m.linear * piece.axes;
    }
  }
  return out;
}

Polyline flatten(const SubPath& s, double tolerance_mm) {
  Polyline out{s.start};
  Vec2 from = s.start;
  for (const auto& piece : s.pieces) {
    switch (piece.kind) {
      case CurveKind::Line: out.push_back(piece.p[0]); break;
      case CurveKind::Cubic: {
        const Cubic q{from, piece.p[0], piece.p[1], piece.p[2]};
        flatten_cubic(q, tolerance_mm, cubic_depth(q, tolerance_mm), out);
        break;
      }
      case CurveKind::Arc: flatten_arc(piece, tolerance_mm, out); break;
    }
    from = piece.end();
  }
  return out;
}

double flatten_point_bound(const SubPath& s, double tolerance_mm) {
  double n = 1.0;
  Vec2 from = s.start;
  for (const auto& piece : s.pieces) {
    switch (piece.kind) {
      case CurveKind::Line:
        n += 1.0;
        break;
      case CurveKind::Cubic:
        n += std::ldexp(1.0, cubic_depth({from, piece.p[0], piece.p[1], piece.p[2]}, tolerance_mm));
        break;
      case CurveKind::Arc:
        n += arc_steps(piece, tolerance_mm);
        break;
    }
    from = piece.end();
  }
  return n;
}

std::pair<Vec2, Vec2> curve_bounds(const SubPath& s) {
  std::pair<Vec2, Vec2> box{s.start, s.start};
  Vec2 from = s.start;
  for (const auto& piece : s.pieces) {
    if (piece.kind == CurveKind::Cubic)
      cubic_extrema({from, piece.p[0], piece.p[1], piece.p[2]}, box);
    if (piece.kind == CurveKind::Arc) arc_extrema(piece, box);
    from = piece.end();
    extend(box, from);
  }
  return box;
}

double max_abs_coordinate(const SubPath& s) {
  double m = 0.0;
  for (int i = 0; i < 2; ++i) take_abs(s.start[i], m);
  for (const auto& piece : s.pieces) {
    for (int i = 0; i < 2; ++i) {
      if (piece.kind == CurveKind::Arc) {
        take_abs(
            std::abs(piece.center[i]) + std::abs(piece.axes(i, 0)) + std::abs(piece.axes(i, 1)), m);
      } else {
        for (int k = 0; k < (piece.kind == CurveKind::Cubic ? 3 : 1); ++k)
          take_abs(piece.p[k][i], m);
      }
    }
  }
  return m;
}

}  // namespace strand::slicer
