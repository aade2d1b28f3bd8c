// A uniform grid over points for nearest-neighbour queries (ordering pen strokes).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "slicer/geometry.h"

namespace strand::post {

class PointGrid {
 public:
  // Cell size chosen for about two points per cell.
  explicit PointGrid(const std::vector<slicer::Vec2>& points);
  // A grid over only the listed ids of `points` (ids keep their meaning); used to rebuild a
  // sparser grid when most points are gone, so searches stop crossing empty cells.
  PointGrid(const std::vector<slicer::Vec2>& points, const std::vector<int>& ids);
  // Nearest point for which alive(id) holds, or -1; ties go to the smaller id.
  template <class Alive>
  int nearest(const slicer::Vec2& q, Alive alive) const;
  // Up to k nearest ids other than those with skip(id), nearest first (ties by id).
  template <class Skip>
  std::vector<int> k_nearest(const slicer::Vec2& q, int k, Skip skip) const;
  // Removes dead ids from the cell holding `id` when queries keep stepping over them.
  void forget(int id);

 private:
  int cell_x(double x) const;
  int cell_y(double y) const;
  const std::vector<slicer::Vec2>& points_;
  slicer::Vec2 lo_ = slicer::Vec2::Zero();
  double cell_ = 1.0;
  int nx_ = 1, ny_ = 1;
  std::vector<std::vector<int>> cells_;
};

template <class Alive>
int PointGrid::nearest(const slicer::Vec2& q, Alive alive) const {
  const int cx = cell_x(q.x()), cy = cell_y(q.y());
  int best = -1;
  double best_d = 0.0;
  const int max_ring = std::max(nx_, ny_) + std::max(std::abs(cx), std::abs(cy)) + 1;
  for (int r = 0; r <= max_ring; ++r) {
    // Every point in ring r is at least (r - 1) * cell away from q.
    if (best >= 0 && (r - 1) * cell_ > std::sqrt(best_d)) break;
    for (int y = cy - r; y <= cy + r; ++y) {
      if (y < 0 || y >= ny_) continue;
      const bool edge_row = (y == cy - r || y == cy + r);
      for (int x = cx - r; x <= cx + r; x += (edge_row ? 1 : 2 * std::max(r, 1))) {
        if (x < 0 || x >= nx_) continue;
        for (int id : cells_[static_cast<std::size_t>(y) * nx_ + x]) {
          if (!alive(id)) continue;
          const double d = (points_[id] - q).squaredNorm();
          if (best < 0 || d < best_d || (d == best_d && id < best)) {
            best = id;
            best_d = d;
          }
        }
      }
    }
  }
  return best;
}

template <class Skip>
std::vector<int> PointGrid::k_nearest(const slicer::Vec2& q, int k, Skip skip) const {
  std::vector<std::pair<double, int>> found;
  const int cx = cell_x(q.x()), cy = cell_y(q.y());
  const int max_ring = std::max(nx_, ny_) + 1;
  for (int r = 0; r <= max_ring; ++r) {
    if (static_cast<int>(found.size()) >= k && (r - 1) * cell_ > std::sqrt(found[k - 1].first)) break;
    for (int y = cy - r; y <= cy + r; ++y) {
      if (y < 0 || y >= ny_) continue;
      const bool edge_row = (y == cy - r || y == cy + r);
      for (int x = cx - r; x <= cx + r; x += (edge_row ? 1 : 2 * std::max(r, 1))) {
        if (x < 0 || x >= nx_) continue;
        for (int id : cells_[static_cast<std::size_t>(y) * nx_ + x]) {
          if (!skip(id)) found.emplace_back((points_[id] - q).squaredNorm(), id);
        }
      }
    }
    std::sort(found.begin(), found.end());
    if (static_cast<int>(found.size()) > k) found.resize(k);
  }
  std::vector<int> ids;
  for (const auto& f : found) ids.push_back(f.second);
  return ids;
}

}  // namespace strand::post
