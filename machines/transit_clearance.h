// How far a held workpiece is from the nozzle (robot_transit.h): the nozzle's cone and the
// extruder's body as a solid of revolution, the workpiece's surface sampled and grouped, a
// lower bound of the distance for a workpiece pose, and CGAL's exact cone test.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <utility>
#include <vector>

#include "machines/holder_profile.h"
#include "machines/robot_transit.h"
#include "slicer/mesh_collision.h"
#include "slicer/units.h"

namespace strand::machines::transit {

// The workpiece's surface is sampled this far apart (coarser for a large mesh, so that about
// kMaxPoints points are taken); every surface point is within kCoverFactor spacings of one.
constexpr double kPointSpacingMm = 0.75;
constexpr double kCoverFactor = 2.0;
constexpr std::size_t kMaxPoints = 200000;
// Samples are grouped in cubes this large, each tested by its bounding sphere first.
constexpr double kClusterMm = 8.0;
// The nozzle's outside as a solid of revolution about the nozzle axis: the cone (a frustum,
// tip_radius at the tip, widening up to length) and the keep-out above it (a cylinder). The
// signed distance of a point: negative inside, by its (axial, radial) coordinates. Plain
// doubles: this runs for every sample of every motion (and unoptimised Eigen expressions cost
// 50x under the sanitizers).
class NozzleSolid {
 public:
  explicit NozzleSolid(const RobotCell& cell) {
    const auto& c = cell.nozzle_cone;
    const double r1 = c.tip_radius_mm + c.length_mm * std::tan(slicer::deg_to_rad(c.half_angle_deg));
    cone_ = {{{0.0, 0.0}, {0.0, c.tip_radius_mm}, {c.length_mm, r1}, {c.length_mm, 0.0}}};
    const auto& k = cell.keep_out;
    has_body_ = k.radius_mm > 0.0 && k.length_mm > 0.0;
    const double top = c.length_mm + k.length_mm;
    body_ = {{{c.length_mm, 0.0}, {c.length_mm, k.radius_mm}, {top, k.radius_mm}, {top, 0.0}}};
  }

  // `a` along the axis from the tip towards the extruder, `r` from the axis.
  double distance(double a, double r, bool cone) const {
    double best = std::numeric_limits<double>::infinity();
    if (cone) best = signed_distance(cone_, a, r);
    if (has_body_) best = std::min(best, signed_distance(body_, a, r));
    return best;
  }

 private:
  using Quad = std::array<std::array<double, 2>, 4>;  // corners 0..3; edge 3 -> 0 on the axis

  static double signed_distance(const Quad& poly, double qa, double qr) {
    double outside = std::numeric_limits<double>::infinity(), inside = outside;
    bool in = true;
    for (int e = 0; e < 4; ++e) {
      const double ax = poly[e][0], ay = poly[e][1];
      const double vx = poly[(e + 1) % 4][0] - ax, vy = poly[(e + 1) % 4][1] - ay;
      const double wx = qa - ax, wy = qr - ay;
      const double len2 = vx * vx + vy * vy;
      const double t = len2 > 0.0 ? std::clamp((wx * vx + wy * vy) / len2, 0.0, 1.0) : 0.0;
      const double dx = wx - t * vx, dy = wy - t * vy;
      const double dist2 = dx * dx + dy * dy;
      outside = std::min(outside, dist2);
      if (e != 3) inside = std::min(inside, dist2);  // the axis is no boundary of the solid
      // Corners run clockwise in (a, r): inside is to the right of every edge.
      if (vx * wy - vy * wx > 0.0) in = false;
    }
    return in ? -std::sqrt(inside) : std::sqrt(outside);
  }

  Quad cone_{}, body_{};
  bool has_body_ = false;
};

// The nozzle's tip and axis in the workpiece's frame: (axial, radial) of a workpiece point.
struct NozzleFrame {
  double tx, ty, tz, ux, uy, uz;
  void axial_radial(double px, double py, double pz, double& a, double& r) const {
    const double dx = px - tx, dy = py - ty, dz = pz - tz;
    a = dx * ux + dy * uy + dz * uz;
    r = std::sqrt(std::max(0.0, dx * dx + dy * dy + dz * dz - a * a));
  }
};

class Clearance {
 public:
  Clearance(const RobotCell& cell, const TransitWorkpiece& wp)
      : cell_(cell), wp_(wp), proximity_(wp.mesh), solid_(cell) {
    up_ = -cell.nozzle_axis.normalized();
    sample_surface();
  }

  double bound_radius_mm() const { return radius_mm_; }

  // A lower bound of the distance from the workpiece (with `printed` mm of layers on it) to
  // the keep-out and (`cone`) the cone, with the workpiece at `w`; negative: how deep inside.
  double lower_bound(const Eigen::Isometry3d& w, double printed, bool cone) const {
    const Eigen::Isometry3d inv = w.inverse();
    const Vec3 tip = inv * cell_.nozzle_tip_mm, up = inv.linear() * up_;
    const NozzleFrame f{tip.x(), tip.y(), tip.z(), up.x(), up.y(), up.z()};
    // Clusters nearest first by their bounding spheres; the rest are skipped once a sphere's
    // bound passes the best point.
    std::vector<std::pair<double, std::size_t>> order(clusters_.size());
    for (std::size_t k = 0; k < clusters_.size(); ++k) {
      const Cluster& c = clusters_[k];
      double a = 0.0, r = 0.0;
      f.axial_radial(c.x, c.y, c.z, a, r);
      order[k] = {solid_.distance(a, r, cone) - c.radius, k};
    }
    std::sort(order.begin(), order.end());
    double best = std::numeric_limits<double>::infinity();
    for (const auto& [bound, k] : order) {
      if (bound >= best) break;
      const Cluster& c = clusters_[k];
      for (std::size_t i = c.first; i < c.last; ++i) {
        double a = 0.0, r = 0.0;
        f.axial_radial(xs_[i], ys_[i], zs_[i], a, r);
        best = std::min(best, solid_.distance(a, r, cone));
      }
    }
    double lb = best - kCoverFactor * spacing_ - printed;
    if (wp_.cylinder_radius_mm) {
      // A cylinder swallowing the nozzle's tip has no sample inside the nozzle.
      if (std::hypot(tip.x(), tip.y()) < *wp_.cylinder_radius_mm + printed && tip.z() > 0.0 &&
          tip.z() < wp_.cylinder_length_mm)
        lb = std::min(lb, -1.0);
    }
    return lb;
  }

  // Exact: does the substrate (without printed layers) enter the cone with the workpiece at w?
  bool cone_hits(const Eigen::Isometry3d& w) const {
    const Eigen::Isometry3d inv = w.inverse();
    return proximity_.cone_hit(cell_.nozzle_cone, inv * cell_.nozzle_tip_mm, inv.linear() * up_)
        .has_value();
  }

 private:
  struct Cluster {  // samples first..last (xs_, ys_, zs_), within radius of (x, y, z)
    double x, y, z, radius;
    std::size_t first, last;
  };

  // Points on every triangle (a barycentric grid no coarser than the spacing), grouped by
  // cube in a deterministic order.
  void sample_surface() {
    const auto& m = wp_.mesh;
    double area = 0.0;
    for (std::size_t t = 0; t < m.triangles.size(); ++t)
      area += 0.5 * slicer::triangle_double_area_mm2(m, static_cast<int>(t));
    spacing_ = std::max(kPointSpacingMm,
                        std::sqrt(2.0 * area / static_cast<double>(kMaxPoints)));
    // Long slivers add a row each per spacing: widen the spacing until the samples the rows
    // below take stay within a bound (the work is bounded before it is done).
    const auto estimate = [&](double sp) {
      double n = 0.0;
      for (std::size_t t = 0; t < m.triangles.size(); ++t) {
        const auto& tri = m.triangles[t];
        const Vec3 &a = m.vertices_mm[tri[0]], &b = m.vertices_mm[tri[1]], &c = m.vertices_mm[tri[2]];
        const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
        n += longest / sp + slicer::triangle_double_area_mm2(m, static_cast<int>(t)) / (sp * sp) + 3.0;
      }
      return n;
    };
    for (int k = 0; k < 200 && estimate(spacing_) > 4.0 * static_cast<double>(kMaxPoints); ++k)
      spacing_ *= 1.5;
    std::map<std::array<long long, 3>, std::vector<Vec3>> cubes;
    const auto add = [&](const Vec3& p) {
      radius_mm_ = std::max(radius_mm_, p.norm());
      const auto cell = [](double v) {
        return static_cast<long long>(std::clamp(std::floor(v / kClusterMm), -1e15, 1e15));
      };
      cubes[{cell(p.x()), cell(p.y()), cell(p.z())}].push_back(p);
    };
    // Rows parallel to the shortest edge, at most a spacing apart along the other two, points
    // at most a spacing apart on each row: every point of the triangle is within
    // kCoverFactor spacings of a sample.
    for (const auto& tri : m.triangles) {
      std::array<Vec3, 3> v = {m.vertices_mm[tri[0]], m.vertices_mm[tri[1]], m.vertices_mm[tri[2]]};
      int shortest = 0;  // the edge v[k] -> v[k+1] opposite the apex v[k+2]
      for (int k = 1; k < 3; ++k)
        if ((v[(k + 1) % 3] - v[k]).norm() < (v[(shortest + 1) % 3] - v[shortest]).norm())
          shortest = k;
      const Vec3 b = v[shortest], c = v[(shortest + 1) % 3], a = v[(shortest + 2) % 3];
      const auto count = [&](double length) {
        return static_cast<int>(std::clamp(std::ceil(length / spacing_), 1.0, 100000.0));
      };
      const int rows = count(std::max((b - a).norm(), (c - a).norm()));
      for (int i = 0; i <= rows; ++i) {
        const double t = static_cast<double>(i) / rows;
        const Vec3 from = a + (b - a) * t, to = a + (c - a) * t;
        const int n = i == 0 ? 0 : count((to - from).norm());
        for (int j = 0; j <= n; ++j) add(n == 0 ? from : from + (to - from) * (static_cast<double>(j) / n));
      }
    }
    for (auto& [key, pts] : cubes) {
      Vec3 centre = Vec3::Zero();
      for (const Vec3& p : pts) centre += p;
      centre /= static_cast<double>(pts.size());
      Cluster c{centre.x(), centre.y(), centre.z(), 0.0, xs_.size(), 0};
      for (const Vec3& p : pts) {
        c.radius = std::max(c.radius, (p - centre).norm());
        xs_.push_back(p.x());
        ys_.push_back(p.y());
        zs_.push_back(p.z());
      }
      c.last = xs_.size();
      clusters_.push_back(c);
    }
  }

  const RobotCell& cell_;
  const TransitWorkpiece& wp_;
  slicer::MeshProximity proximity_;
  NozzleSolid solid_;
  std::vector<double> xs_, ys_, zs_;  // the samples, cluster by cluster
  std::vector<Cluster> clusters_;
  Vec3 up_ = Vec3::UnitZ();
  double spacing_ = kPointSpacingMm;
  double radius_mm_ = 0.0;
};

}  // namespace strand::machines::transit
