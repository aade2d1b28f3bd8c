// Adaptive bisection of a segment's parameter until every mapped chord is within tolerance.
#include "postprocess/plan/surface_sampling.h"

#include <algorithm>
#include <cmath>

#include "slicer/geometry.h"
#include "slicer/units.h"

namespace strand::post {

using slicer::Vec3;

namespace {

// Deepest bisection below one starting piece: 2^24 chords, far beyond any tolerance the
// parameters allow; a guard against non-finite input, not a working limit.
constexpr int kMaxDepth = 24;
// Starting pieces turn at most this much (around the cylinder or along an arc), rad, so the
// midpoint test cannot miss a bulge that returns to the chord.
constexpr double kMaxStartTurnRad = slicer::kPi / 8;

// The segment as a curve in (u, v) over t in [0, 1].
struct Curve {
  Vec2 from, to, center;
  double radius = 0.0, a0 = 0.0, sweep = 0.0;
  bool arc = false;

  Vec2 at(double t) const {
    if (!arc) return from + t * (to - from);
    if (t >= 1.0) return to;
    return slicer::on_circle(center, radius, a0 + sweep * t);
  }
};

Curve curve_of(const Vec2& from, const slicer::Segment& s) {
  Curve c{from, s.end_mm, s.center_mm};
  if (s.kind == slicer::SegmentKind::Arc && (s.end_mm - from).norm() > 0.0) {
    c.arc = true;
    c.radius = (from - s.center_mm).norm();
    c.a0 = slicer::angle_of(s.center_mm, from);
    c.sweep = slicer::arc_sweep(s.center_mm, from, s.end_mm, s.ccw);
  }
  return c;
}

double distance_to_chord(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  if (len2 <= 0.0) return (p - a).norm();
  const double t = std::clamp((p - a).dot(ab) / len2, 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

class Sampler {
 public:
  Sampler(const slicer::Surface& s, const Curve& c, double offset, double tol)
      : s_(s), c_(c), offset_(offset), tol_(tol) {}

  // Appends the points of (t0, t1] whose chords are within tolerance.
  void refine(double t0, const Vec3& p0, double t1, const Vec3& p1, int depth,
              std::vector<Vec2>& out) const {
    const double tm = 0.5 * (t0 + t1);
    const Vec3 pm = map(tm);
    // Written as "not above" so a non-finite distance stops the bisection.
    const bool fine = !(distance_to_chord(pm, p0, p1) > tol_ ||
                        distance_to_chord(map(0.5 * (t0 + tm)), p0, p1) > tol_ ||
                        distance_to_chord(map(0.5 * (tm + t1)), p0, p1) > tol_);
    if (fine || depth >= kMaxDepth) {
      out.push_back(c_.at(t1));
      return;
    }
    refine(t0, p0, tm, pm, depth + 1, out);
    refine(tm, pm, t1, p1, depth + 1, out);
  }

  Vec3 map(double t) const { return s_.frame_at(c_.at(t), offset_).point_mm; }

 private:
  const slicer::Surface& s_;
  const Curve& c_;
  double offset_, tol_;
};

// Turn of the mapped segment around a closed surface plus its own arc sweep, rad.
double turning(const slicer::Surface& s, const Curve& c, double offset) {
  double turn = std::abs(c.sweep);
  if (auto period = s.u_period_mm(offset)) {
    double u_lo = std::min(c.from.x(), c.to.x()), u_hi = std::max(c.from.x(), c.to.x());
    if (c.arc)
      u_lo = std::min(u_lo, c.center.x() - c.radius),
      u_hi = std::max(u_hi, c.center.x() + c.radius);
    turn += slicer::kTwoPi * (u_hi - u_lo) / *period;
  }
  return turn;
}

}  // namespace

std::vector<Vec2> sample_on_surface(const slicer::Surface& surface, const Vec2& from,
                                    const slicer::Segment& segment, double offset_mm,
                                    double tolerance_mm) {
  const Curve c = curve_of(from, segment);
  const Sampler sampler(surface, c, offset_mm, tolerance_mm);
  const int pieces =
      std::max(1, static_cast<int>(std::ceil(turning(surface, c, offset_mm) / kMaxStartTurnRad)));
  std::vector<Vec2> out;
  Vec3 p0 = sampler.map(0.0);
  for (int k = 0; k < pieces; ++k) {
    const double t0 = double(k) / pieces, t1 = double(k + 1) / pieces;
    const Vec3 p1 = sampler.map(t1);
    sampler.refine(t0, p0, t1, p1, 0, out);
    p0 = p1;
  }
  out.back() = segment.end_mm;  // exact end, whatever the rounding of the parameter
  return out;
}

std::size_t sample_bound(const slicer::Surface& surface, const Vec2& from,
                         const slicer::Segment& segment, double offset_mm, double tolerance_mm) {
  const Curve c = curve_of(from, segment);
  const slicer::SurfaceFrame f = surface.frame_at(from, offset_mm);
  const double stretch = std::max({f.d_du.norm(), f.d_dv.norm(), 1.0});
  const double length = slicer::segment_length(from, segment) * stretch;
  // Curvature of the mapped curve: the pattern's own arc (shrunk at most by the inverse
  // stretch) plus the surface's bending; for a cylinder 1 / (radius + offset).
  double kappa = c.arc && c.radius > 0 ? stretch / c.radius : 0.0;
  if (auto period = surface.u_period_mm(offset_mm)) kappa += slicer::kTwoPi / *period * stretch;
  const double pieces = std::ceil(turning(surface, c, offset_mm) / kMaxStartTurnRad) + 1.0;
  // Chords of length sqrt(8 tol / kappa) keep the sagitta within tol; bisection may halve
  // once more than needed.
  const double chords = length * std::sqrt(kappa / (8.0 * tolerance_mm)) * 2.0;
  return static_cast<std::size_t>(std::min(pieces + chords, 1e15));
}

}  // namespace strand::post
