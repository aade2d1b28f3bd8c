// Curve evaluation, transforms and bounded-error flattening.
#include "slicer/curves.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

namespace strand::slicer {

namespace {

// Deepest de Casteljau split: 2^-40 of a curve is far below any pen's resolution.
constexpr int kMaxSplitDepth = 40;
// An arc is never cut into more steps than this (a 100 m circle at 1 µm stays well below).
constexpr int kMaxArcSteps = 1 << 20;

struct Cubic {
  Vec2 a, b, c, d;
};

void flatten_cubic(const Cubic& q, double tol, int depth, Polyline& out) {
  const double err = std::max(point_segment_distance(q.b, q.a, q.d),
                              point_segment_distance(q.c, q.a, q.d));
  if (err <= tol || depth >= kMaxSplitDepth) {
    out.push_back(q.d);
    return;
  }
  const Vec2 ab = (q.a + q.b) / 2, bc = (q.b + q.c) / 2, cd = (q.c + q.d) / 2;
  const Vec2 abc = (ab + bc) / 2, bcd = (bc + cd) / 2, mid = (abc + bcd) / 2;
  flatten_cubic({q.a, ab, abc, mid}, tol, depth + 1, out);
  flatten_cubic({mid, bcd, cd, q.d}, tol, depth + 1, out);
}

void flatten_arc(const CurvePiece& arc, double tol, Polyline& out) {
  const double sigma = Eigen::JacobiSVD<Eigen::Matrix2d>(arc.axes).singularValues()(0);
  int n = 1;
  if (sigma > tol) {
    // 1 - cos(step / 2) <= tol / sigma  <=>  step <= 2 acos(1 - tol / sigma)
    const double step = 2.0 * std::acos(std::max(-1.0, 1.0 - tol / sigma));
    n = static_cast<int>(std::ceil(std::abs(arc.sweep_rad) / step));
  }
  n = std::clamp(n, 1, kMaxArcSteps);
  for (int i = 1; i <= n; ++i) out.push_back(arc_point(arc, arc.t0_rad + arc.sweep_rad * i / n));
}

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
      case CurveKind::Cubic:
        flatten_cubic({from, piece.p[0], piece.p[1], piece.p[2]}, tolerance_mm, 0, out);
        break;
      case CurveKind::Arc: flatten_arc(piece, tolerance_mm, out); break;
    }
    from = piece.end();
  }
  return out;
}

}  // namespace strand::slicer
