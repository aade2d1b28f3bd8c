// Forward and inverse plotter kinematics, drawable area and adaptive segment splitting.
#include "machines/plotter_kinematics.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "slicer/geometry.h"
#include "slicer/params.h"

namespace strand::machines {

namespace {

// Pieces shorter than this are never split further (a motor step is larger), mm.
constexpr double kMinSplitMm = 1e-3;
constexpr int kMaxSplitDepth = 24;
// Grid cells per side when searching the polargraph's drawable rectangle.
constexpr int kAreaGrid = 160;

// Attachment point of the cables relative to the left nail, in a frame where the right
// nail sits at (motor_distance - gondola_width, 0).
Vec2 attachment(const PlotterSetup& s, const Vec2& p) {
  return Vec2(p.x() - s.gondola_width_mm / 2, p.y() - s.pen_offset_mm);
}

double span(const PlotterSetup& s) { return s.motor_distance_mm - s.gondola_width_mm; }

Eigen::Matrix2d jacobian(const PlotterSetup& s, const Vec2& p) {
  const double h = 1e-4;
  Eigen::Matrix2d j;
  j.col(0) = (to_axes(s, p + Vec2(h, 0)) - to_axes(s, p - Vec2(h, 0))) / (2 * h);
  j.col(1) = (to_axes(s, p + Vec2(0, h)) - to_axes(s, p - Vec2(0, h))) / (2 * h);
  return j;
}

std::string num(double v) { return slicer::short_number(std::round(v * 1000.0) / 1000.0); }

double max_bow(const PlotterSetup& s, const Vec2& a, const Vec2& b, const Vec2& pa, const Vec2& pb) {
  const Vec2 A = to_axes(s, pa), B = to_axes(s, pb);
  double worst = 0.0;
  for (int i = 1; i < 8; ++i) {
    const Vec2 q = to_paper(s, A + (B - A) * (i / 8.0));
    worst = std::max(worst, slicer::point_segment_distance(q, a, b));
  }
  return worst;
}

void split(const PlotterSetup& s, const Vec2& a, const Vec2& b, const Vec2& pa, const Vec2& pb,
           double tol, int depth, std::vector<Vec2>& out) {
  if (depth >= kMaxSplitDepth || (pb - pa).norm() < kMinSplitMm ||
      max_bow(s, a, b, pa, pb) <= 0.9 * tol) {
    out.push_back(pb);
    return;
  }
  const Vec2 mid = (pa + pb) / 2;
  split(s, a, b, pa, mid, tol, depth + 1, out);
  split(s, a, b, mid, pb, tol, depth + 1, out);
}

}  // namespace

bool paper_y_down(PlotterKind k) { return k != PlotterKind::Xy; }

Vec2 to_axes(const PlotterSetup& s, const Vec2& p) {
  switch (s.kind) {
    case PlotterKind::Xy: return p;
    case PlotterKind::Polargraph: {
      const Vec2 q = attachment(s, p);
      return Vec2(q.norm(), Vec2(span(s) - q.x(), q.y()).norm());
    }
    case PlotterKind::PolarRTheta: {
      const Vec2 d = s.pivot_mm - p;  // pivot lies right of the paper: d.x > 0
      return Vec2(s.origin_radius_mm - d.norm(), (p.y() - s.pivot_mm.y()) / d.x() * s.lever_mm);
    }
  }
  return p;
}

Vec2 to_paper(const PlotterSetup& s, const Vec2& a) {
  switch (s.kind) {
    case PlotterKind::Xy: return a;
    case PlotterKind::Polargraph: {
      const double d = span(s);
      const double u = (a.x() * a.x() - a.y() * a.y() + d * d) / (2 * d);
      const double v = std::sqrt(std::max(0.0, a.x() * a.x() - u * u));
      return Vec2(u + s.gondola_width_mm / 2, v + s.pen_offset_mm);
    }
    case PlotterKind::PolarRTheta: {
      const double r = s.origin_radius_mm - a.x();
      const double theta = std::atan2(a.y(), s.lever_mm);
      return Vec2(s.pivot_mm.x() - r * std::cos(theta), s.pivot_mm.y() + r * std::sin(theta));
    }
  }
  return a;
}

std::pair<double, double> cable_tension(const PlotterSetup& s, const Vec2& p) {
  const Vec2 q = attachment(s, p);
  const double d = span(s);
  if (q.y() <= 0.0) return {INFINITY, INFINITY};
  const double l1 = q.norm(), l2 = Vec2(d - q.x(), q.y()).norm();
  return {(d - q.x()) * l1 / (q.y() * d), q.x() * l2 / (q.y() * d)};
}

double resolution_loss(const PlotterSetup& s, const Vec2& p) {
  const auto sv = Eigen::JacobiSVD<Eigen::Matrix2d>(jacobian(s, p)).singularValues();
  return sv(1) > 0.0 ? 1.0 / sv(1) : INFINITY;
}

std::optional<std::string> unreachable_reason(const Plotter& pl, const Vec2& p) {
  if (!std::isfinite(p.x()) || !std::isfinite(p.y())) return "a coordinate is not a finite number";
  const char* axis[2] = {"x", "y"};
  const double slack = 1e-6;
  for (int i = 0; i < 2; ++i) {
    if (p[i] < pl.area_min_mm[i] - slack) return std::string(axis[i]) + " " + num(p[i]) + " mm < " + num(pl.area_min_mm[i]) + " mm";
    if (p[i] > pl.area_max_mm[i] + slack) return std::string(axis[i]) + " " + num(p[i]) + " mm > " + num(pl.area_max_mm[i]) + " mm";
  }
  const PlotterSetup& s = pl.setup;
  if (s.kind != PlotterKind::Polargraph) return std::nullopt;
  const auto [tl, tr] = cable_tension(s, p);
  for (const auto& [name, t] : {std::pair{"left", tl}, std::pair{"right", tr}}) {
    if (t < s.min_tension) return std::string(name) + " cable tension " + num(t) + " x the gondola weight < " + num(s.min_tension) + " (the pen would swing)";
    if (t > s.max_tension) return std::string(name) + " cable tension " + num(t) + " x the gondola weight > " + num(s.max_tension) + " (too close to the motor line)";
  }
  const double loss = resolution_loss(s, p);
  if (loss > s.max_resolution_loss) return "resolution loss " + num(loss) + " > " + num(s.max_resolution_loss) + " (cables nearly parallel)";
  return std::nullopt;
}

std::pair<Vec2, Vec2> drawable_area(const Plotter& pl) {
  if (pl.setup.kind != PlotterKind::Polargraph) return {pl.area_min_mm, pl.area_max_mm};
  // Grid over the paper; per row, the half-width around the centre line that stays valid.
  const Vec2 lo = pl.area_min_mm, hi = pl.area_max_mm;
  const double cx = pl.setup.home_mm.x();
  const double dy = (hi.y() - lo.y()) / kAreaGrid;
  const double dx = std::min(cx - lo.x(), hi.x() - cx) / kAreaGrid;
  std::vector<int> half(kAreaGrid + 1, 0);
  for (int r = 0; r <= kAreaGrid; ++r) {
    const double y = lo.y() + r * dy;
    int k = 0;
    while (k <= kAreaGrid && !unreachable_reason(pl, Vec2(cx - k * dx, y)) &&
           !unreachable_reason(pl, Vec2(cx + k * dx, y))) {
      ++k;
    }
    half[r] = k - 1;  // -1: the centre itself is out
  }
  double best = 0.0;
  std::pair<Vec2, Vec2> area{Vec2(cx, lo.y()), Vec2(cx, lo.y())};
  for (int top = 0; top <= kAreaGrid; ++top) {
    int h = kAreaGrid;
    for (int bottom = top; bottom <= kAreaGrid; ++bottom) {
      h = std::min(h, half[bottom]);
      if (h <= 1) break;
      // one cell of margin on every side, since validity was only sampled on the grid
      const double w = 2 * (h - 1) * dx, height = (bottom - top - 2) * dy;
      if (height > 0 && w * height > best) {
        best = w * height;
        area = {Vec2(cx - (h - 1) * dx, lo.y() + (top + 1) * dy),
                Vec2(cx + (h - 1) * dx, lo.y() + (bottom - 1) * dy)};
      }
    }
  }
  return area;
}

double rounding_error_mm(const PlotterSetup& s, const Vec2& p, int decimals) {
  const double digit = 0.5 * std::pow(10.0, -decimals);
  const double ex = std::max(digit, 0.5 / s.steps_per_mm.x());
  const double ey = std::max(digit, 0.5 / s.steps_per_mm.y());
  const double loss = s.kind == PlotterKind::Xy ? 1.0 : resolution_loss(s, p);
  return loss * std::hypot(ex, ey);
}

std::vector<Vec2> split_for_axes(const PlotterSetup& s, const Vec2& a, const Vec2& b,
                                 double tolerance_mm) {
  std::vector<Vec2> out;
  if (s.kind == PlotterKind::Xy) {
    out.push_back(b);
    return out;
  }
  split(s, a, b, a, b, tolerance_mm, 0, out);
  return out;
}

}  // namespace strand::machines
