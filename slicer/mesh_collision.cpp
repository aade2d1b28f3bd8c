// Closest points and nozzle-cone contacts with a CGAL AABB tree over the mesh's triangles.
#include "slicer/mesh_collision.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <vector>

#include "slicer/units.h"

namespace strand::slicer {

namespace {

using K = CGAL::Simple_cartesian<double>;
using Triangles = std::vector<K::Triangle_3>;
using Primitive = CGAL::AABB_triangle_primitive<K, Triangles::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;

K::Point_3 point(const Vec3& v) { return {v.x(), v.y(), v.z()}; }
Vec3 vec(const K::Point_3& p) { return {p.x(), p.y(), p.z()}; }

// Barycentric weights of q (on or near the plane of a, b, c), clamped into the triangle.
Vec3 barycentric(const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 v0 = b - a, v1 = c - a, v2 = q - a;
  const double d00 = v0.dot(v0), d01 = v0.dot(v1), d11 = v1.dot(v1);
  const double d20 = v2.dot(v0), d21 = v2.dot(v1);
  const double den = d00 * d11 - d01 * d01;
  if (!(den > 0.0)) return Vec3(1.0, 0.0, 0.0);
  const double v = (d11 * d20 - d01 * d21) / den;
  const double w = (d00 * d21 - d01 * d20) / den;
  Vec3 out(1.0 - v - w, v, w);
  out = out.cwiseMax(0.0);
  return out / out.sum();
}

// Golden-section minimum of a convex function on [lo, hi]; returns the argument.
template <class F>
double golden_min(F f, double lo, double hi, int iterations) {
  constexpr double kInv = 0.6180339887498949;
  double a = lo, b = hi;
  double c = b - kInv * (b - a), d = a + kInv * (b - a);
  double fc = f(c), fd = f(d);
  for (int i = 0; i < iterations; ++i) {
    if (fc < fd) {
      b = d, d = c, fd = fc;
      c = b - kInv * (b - a);
      fc = f(c);
    } else {
      a = c, c = d, fc = fd;
      d = a + kInv * (b - a);
      fd = f(d);
    }
  }
  return fc < fd ? c : d;
}

// The frustum as a convex "inside" function: h(x) <= 0 inside (for t in [0, length]).
struct Frustum {
  Vec3 tip, up;
  double r0, slope, length;

  double t(const Vec3& x) const { return (x - tip).dot(up); }
  double h(const Vec3& x) const {
    const Vec3 d = x - tip;
    const double along = d.dot(up);
    return (d - along * up).norm() - r0 - slope * along;
  }
};

// The part of triangle (a, b, c) with 0 <= t <= length (a convex polygon, maybe empty).
std::vector<Vec3> clip(const Frustum& f, const std::array<Vec3, 3>& tri) {
  std::vector<Vec3> poly(tri.begin(), tri.end());
  for (int side = 0; side < 2; ++side) {
    // side 0 keeps t >= 0, side 1 keeps t <= length.
    const auto keep = [&](const Vec3& p) { return side == 0 ? f.t(p) : f.length - f.t(p); };
    std::vector<Vec3> out;
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const Vec3& p = poly[i];
      const Vec3& q = poly[(i + 1) % poly.size()];
      const double kp = keep(p), kq = keep(q);
      if (kp >= 0.0) out.push_back(p);
      if ((kp >= 0.0) != (kq >= 0.0)) out.push_back(p + (kp / (kp - kq)) * (q - p));
    }
    poly = std::move(out);
    if (poly.empty()) break;
  }
  return poly;
}

// Smallest h over a convex polygon (nested golden sections: h is convex, and its minimum over
// the chords across the polygon is convex in the chord's position). Returns that point.
Vec3 minimise(const Frustum& f, const std::vector<Vec3>& poly) {
  std::size_t far = 1;
  for (std::size_t i = 1; i < poly.size(); ++i)
    if ((poly[i] - poly[0]).squaredNorm() > (poly[far] - poly[0]).squaredNorm()) far = i;
  const Vec3 e1 = (poly[far] - poly[0]).normalized();
  std::vector<double> s(poly.size());
  for (std::size_t i = 0; i < poly.size(); ++i) s[i] = (poly[i] - poly[0]).dot(e1);
  const double lo = *std::min_element(s.begin(), s.end());
  const double hi = *std::max_element(s.begin(), s.end());
  // The chord at position x along e1: its two end points on the polygon's edges.
  const auto chord = [&](double x, Vec3& a, Vec3& b) {
    bool first = true;
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const std::size_t j = (i + 1) % poly.size();
      const double si = s[i], sj = s[j];
      if ((x < std::min(si, sj)) || (x > std::max(si, sj))) continue;
      const Vec3 p =
          sj == si ? poly[i] : Vec3(poly[i] + (x - si) / (sj - si) * (poly[j] - poly[i]));
      if (first)
        a = b = p, first = false;
      else if ((p - a).squaredNorm() > (b - a).squaredNorm())
        b = p;
    }
    if (first) a = b = poly[0];
  };
  const auto best_on_chord = [&](double x) {
    Vec3 a = Vec3::Zero(), b = Vec3::Zero();
    chord(x, a, b);
    const double l = golden_min([&](double u) { return f.h(a + u * (b - a)); }, 0.0, 1.0, 40);
    return Vec3(a + l * (b - a));
  };
  const double x = golden_min([&](double v) { return f.h(best_on_chord(v)); }, lo, hi, 40);
  return best_on_chord(x);
}

}  // namespace

struct MeshProximity::Impl {
  std::vector<std::array<Vec3, 3>> corners;
  Triangles triangles;
  Tree tree;
};

MeshProximity::MeshProximity(const Mesh& mesh) : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  for (const auto& t : mesh.triangles) {
    const std::array<Vec3, 3> c{mesh.vertices_mm[t[0]], mesh.vertices_mm[t[1]],
                                mesh.vertices_mm[t[2]]};
    s.corners.push_back(c);
    s.triangles.emplace_back(point(c[0]), point(c[1]), point(c[2]));
  }
  s.tree.insert(s.triangles.cbegin(), s.triangles.cend());
  s.tree.build();
  s.tree.accelerate_distance_queries();
}

MeshProximity::~MeshProximity() = default;

MeshPoint MeshProximity::closest(const Vec3& p) const {
  const auto [q, id] = impl_->tree.closest_point_and_primitive(point(p));
  MeshPoint out;
  out.triangle = static_cast<int>(std::distance(impl_->triangles.cbegin(), id));
  const auto& c = impl_->corners[static_cast<std::size_t>(out.triangle)];
  out.point_mm = vec(q);
  out.barycentric = barycentric(out.point_mm, c[0], c[1], c[2]);
  out.distance_mm = (out.point_mm - p).norm();
  return out;
}

std::optional<MeshPoint> MeshProximity::first_hit(const Vec3& from, const Vec3& to) const {
  std::vector<Primitive::Id> near;
  impl_->tree.all_intersected_primitives(K::Segment_3(point(from), point(to)),
                                         std::back_inserter(near));
  const Vec3 d = to - from;
  std::optional<MeshPoint> best;
  for (const auto& id : near) {
    const int index = static_cast<int>(std::distance(impl_->triangles.cbegin(), id));
    const auto& c = impl_->corners[static_cast<std::size_t>(index)];
    // Moller-Trumbore: from + s d = c0 + b1 (c1 - c0) + b2 (c2 - c0).
    const Vec3 e1 = c[1] - c[0], e2 = c[2] - c[0];
    const Vec3 h = d.cross(e2);
    const double det = e1.dot(h);
    if (std::abs(det) < 1e-15 * e1.norm() * e2.norm() * d.norm()) continue;  // edge-on
    const Vec3 r = from - c[0];
    const double b1 = r.dot(h) / det;
    const Vec3 q = r.cross(e1);
    const double b2 = d.dot(q) / det;
    const double s = e2.dot(q) / det;
    constexpr double kEdge = 1e-9;  // a hit on a shared edge counts for both triangles
    if (b1 < -kEdge || b2 < -kEdge || b1 + b2 > 1.0 + kEdge || s < 0.0 || s > 1.0) continue;
    if (best && s * d.norm() >= best->distance_mm) continue;
    MeshPoint m;
    m.triangle = index;
    m.barycentric = Vec3(1.0 - b1 - b2, b1, b2).cwiseMax(0.0);
    m.barycentric /= m.barycentric.sum();
    m.point_mm = from + s * d;
    m.distance_mm = s * d.norm();
    best = m;
  }
  return best;
}

std::optional<Vec3> MeshProximity::cone_hit(const NozzleCone& cone, const Vec3& tip,
                                            const Vec3& up) const {
  const Frustum f{tip, up.normalized(), cone.tip_radius_mm,
                  std::tan(deg_to_rad(cone.half_angle_deg)), cone.length_mm};
  if (!(f.length > 0.0)) return std::nullopt;
  // Bounding box of the frustum: its two end discs.
  const double r1 = f.r0 + f.slope * f.length;
  Vec3 lo = tip, hi = tip;
  for (const auto& [centre, r] :
       {std::pair{tip, f.r0}, std::pair{Vec3(tip + f.length * f.up), r1}}) {
    for (int k = 0; k < 3; ++k) {
      const double extent = r * std::sqrt(std::max(0.0, 1.0 - f.up[k] * f.up[k]));
      lo[k] = std::min(lo[k], centre[k] - extent);
      hi[k] = std::max(hi[k], centre[k] + extent);
    }
  }
  std::vector<Primitive::Id> near;
  impl_->tree.all_intersected_primitives(
      CGAL::Bbox_3(lo.x(), lo.y(), lo.z(), hi.x(), hi.y(), hi.z()), std::back_inserter(near));
  constexpr double kInsideMm = 1e-6;
  const double lipschitz = 1.0 + f.slope;  // |grad h| <= 1 + slope
  std::optional<Vec3> hit;
  double deepest = 0.0;
  for (const auto& id : near) {
    const auto& c =
        impl_->corners[static_cast<std::size_t>(std::distance(impl_->triangles.cbegin(), id))];
    const std::vector<Vec3> poly = clip(f, c);
    if (poly.empty()) continue;
    // Far from the frustum everywhere on the polygon (h is Lipschitz): nothing to search.
    double h_min = f.h(poly[0]), diameter = 0.0;
    Vec3 at = poly[0];
    for (const Vec3& p : poly) {
      if (f.h(p) < h_min) h_min = f.h(p), at = p;
      for (const Vec3& q : poly) diameter = std::max(diameter, (p - q).norm());
    }
    if (h_min - lipschitz * diameter > kInsideMm) continue;
    // The axis through the polygon's plane inside the polygon: h < 0 there.
    const Vec3 n = (c[1] - c[0]).cross(c[2] - c[0]);
    if (std::abs(n.dot(f.up)) > 1e-12 * n.norm()) {
      const double t = (c[0] - tip).dot(n) / f.up.dot(n);
      const Vec3 x = tip + t * f.up;
      const Vec3 b = barycentric(x, c[0], c[1], c[2]);
      if (t >= 0.0 && t <= f.length &&
          (b[0] * c[0] + b[1] * c[1] + b[2] * c[2] - x).norm() < kInsideMm && f.h(x) < h_min)
        h_min = f.h(x), at = x;
    }
    if (diameter > 0.0 && h_min > -kInsideMm) {
      const Vec3 m = minimise(f, poly);
      if (f.h(m) < h_min) h_min = f.h(m), at = m;
    }
    if (h_min <= kInsideMm && (!hit || h_min < deepest)) hit = at, deepest = h_min;
  }
  return hit;
}

}  // namespace strand::slicer
