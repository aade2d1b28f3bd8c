// A uniform grid over points for nearest-neighbour queries (ordering pen strokes). Cells are
// stored flat (one id array, a start and a live count per cell): no allocation per cell or per
// query, and removed ids leave their cell so later searches do not step over them.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "slicer/geometry.h"

namespace strand::post {

class PointGrid {
 public:
  // Most neighbours k_nearest returns.
  static constexpr int kMaxK = 32;

  // Cell size chosen for about two points per cell.
  explicit PointGrid(const std::vector<slicer::Vec2>& points);
  // A grid over only the listed ids of `points` (ids keep their meaning); used to rebuild a
  // sparser grid when most points are gone, so searches stop crossing empty cells.
  PointGrid(const std::vector<slicer::Vec2>& points, const std::vector<int>& ids);
  // Nearest point for which alive(id) holds, or -1; ties go to the smaller id.
  template <class Alive>
  int nearest(const slicer::Vec2& q, Alive alive) const {
    return search(q, -1.0, alive);
  }
  // The same, but only the cells that reach within radius_mm of q are read: the result is
  // the nearest point when that one is within radius_mm (the caller checks).
  template <class Alive>
  int nearest_within(const slicer::Vec2& q, double radius_mm, Alive alive) const {
    return search(q, radius_mm, alive);
  }
  // Up to k (<= kMaxK) nearest ids other than those with skip(id), nearest first (ties by
  // id), written to out; returns how many.
  template <class Skip>
  int k_nearest(const slicer::Vec2& q, int k, Skip skip, int* out) const;
  // Removes `id` from its cell.
  void forget(int id);
  // The live ids cell by cell (rows of cells bottom up, ids rising within a cell): an order in
  // which points near each other mostly sit near each other.
  std::vector<int> ids_by_cell() const;

 private:
  int cell_x(double x) const;
  int cell_y(double y) const;
  std::size_t cell_of(const slicer::Vec2& p) const {
    return static_cast<std::size_t>(cell_y(p.y())) * nx_ + cell_x(p.x());
  }
  // Calls f(id) for every live id in ring r around cell (cx, cy).
  template <class F>
  void ring(int cx, int cy, int r, F f) const;
  template <class Alive>
  int search(const slicer::Vec2& q, double radius_mm, Alive alive) const;

  const std::vector<slicer::Vec2>& points_;
  slicer::Vec2 lo_ = slicer::Vec2::Zero();
  double cell_ = 1.0;
  int nx_ = 1, ny_ = 1;
  std::vector<int> ids_;                 // ids grouped by cell
  std::vector<std::uint32_t> start_;     // first slot of each cell in ids_
  std::vector<std::uint32_t> count_;     // live ids of each cell
};

template <class F>
void PointGrid::ring(int cx, int cy, int r, F f) const {
  for (int y = cy - r; y <= cy + r; ++y) {
    if (y < 0 || y >= ny_) continue;
    const bool edge_row = (y == cy - r || y == cy + r);
    for (int x = cx - r; x <= cx + r; x += (edge_row ? 1 : 2 * std::max(r, 1))) {
      if (x < 0 || x >= nx_) continue;
      const std::size_t c = static_cast<std::size_t>(y) * nx_ + x;
      for (std::uint32_t i = start_[c]; i < start_[c] + count_[c]; ++i) f(ids_[i]);
    }
  }
}

template <class Alive>
int PointGrid::search(const slicer::Vec2& q, double radius_mm, Alive alive) const {
  const int cx = cell_x(q.x()), cy = cell_y(q.y());
  int best = -1;
  double best_d = 0.0;
  const auto consider = [&](int id) {
    if (!alive(id)) return;
    const double d = (points_[id] - q).squaredNorm();
    if (best < 0 || d < best_d || (d == best_d && id < best)) {
      best = id;
      best_d = d;
    }
  };
  if (radius_mm >= 0 && radius_mm < cell_) {
    // A short reach: only the (at most four) cells the square around q touches can hold a
    // point within radius_mm, usually q's own cell alone.
    const int x1 = cell_x(q.x() + radius_mm), y1 = cell_y(q.y() + radius_mm);
    for (int y = cell_y(q.y() - radius_mm); y <= y1; ++y) {
      for (int x = cell_x(q.x() - radius_mm); x <= x1; ++x) {
        const std::size_t c = static_cast<std::size_t>(y) * nx_ + x;
        for (std::uint32_t i = start_[c]; i < start_[c] + count_[c]; ++i) consider(ids_[i]);
      }
    }
    return best;
  }
  const int max_ring = std::max(nx_, ny_) + std::max(std::abs(cx), std::abs(cy)) + 1;
  for (int r = 0; r <= max_ring; ++r) {
    // Every point in ring r is at least (r - 1) * cell away from q.
    if (best >= 0 && (r - 1) * cell_ > std::sqrt(best_d)) break;
    if (radius_mm >= 0 && (r - 1) * cell_ > radius_mm) break;
    ring(cx, cy, r, consider);
  }
  return best;
}

template <class Skip>
int PointGrid::k_nearest(const slicer::Vec2& q, int k, Skip skip, int* out) const {
  k = std::clamp(k, 0, kMaxK);
  std::pair<double, int> found[kMaxK];  // the best so far, sorted by (distance^2, id)
  int n = 0;
  const int cx = cell_x(q.x()), cy = cell_y(q.y());
  const int max_ring = std::max(nx_, ny_) + std::max(std::abs(cx), std::abs(cy)) + 1;
  for (int r = 0; r <= max_ring && k > 0; ++r) {
    if (n >= k && (r - 1) * cell_ > std::sqrt(found[k - 1].first)) break;
    ring(cx, cy, r, [&](int id) {
      if (skip(id)) return;
      const std::pair<double, int> f((points_[id] - q).squaredNorm(), id);
      if (n == k && !(f < found[k - 1])) return;
      int at = n < k ? n++ : k - 1;
      while (at > 0 && f < found[at - 1]) {
        found[at] = found[at - 1];
        --at;
      }
      found[at] = f;
    });
  }
  for (int i = 0; i < n; ++i) out[i] = found[i].second;
  return n;
}

}  // namespace strand::post
