// Uniform grid construction for point queries: ids bucketed by cell with a counting sort.
#include "postprocess/plot/point_grid.h"

#include <algorithm>
#include <cmath>

namespace strand::post {

namespace {

std::vector<int> all_ids(std::size_t n) {
  std::vector<int> ids(n);
  for (std::size_t i = 0; i < n; ++i) ids[i] = static_cast<int>(i);
  return ids;
}

}  // namespace

PointGrid::PointGrid(const std::vector<slicer::Vec2>& points)
    : PointGrid(points, all_ids(points.size())) {}

PointGrid::PointGrid(const std::vector<slicer::Vec2>& points, const std::vector<int>& ids)
    : points_(points) {
  if (ids.empty()) {
    start_.assign(1, 0);
    count_.assign(1, 0);
    return;
  }
  slicer::Vec2 hi = points[ids[0]];
  lo_ = hi;
  for (int id : ids) {
    lo_ = lo_.cwiseMin(points[id]);
    hi = hi.cwiseMax(points[id]);
  }
  const slicer::Vec2 size = (hi - lo_).cwiseMax(slicer::Vec2(1e-9, 1e-9));
  cell_ = std::max(std::sqrt(size.x() * size.y() * 2.0 / static_cast<double>(ids.size())),
                   std::max(size.x(), size.y()) / 4096.0);
  nx_ = std::max(1, static_cast<int>(size.x() / cell_) + 1);
  ny_ = std::max(1, static_cast<int>(size.y() / cell_) + 1);
  const std::size_t cells = static_cast<std::size_t>(nx_) * ny_;
  count_.assign(cells, 0);
  for (int id : ids) ++count_[cell_of(points[id])];
  start_.assign(cells, 0);
  for (std::size_t c = 1; c < cells; ++c) start_[c] = start_[c - 1] + count_[c - 1];
  ids_.resize(ids.size());
  std::vector<std::uint32_t> fill(start_);
  for (int id : ids) ids_[fill[cell_of(points[id])]++] = id;
}

// Clamped before the cast: a query far outside the grid (a travel start of the machine's
// metric, say) would not fit an int.
int PointGrid::cell_x(double x) const {
  return static_cast<int>(std::clamp(std::floor((x - lo_.x()) / cell_), 0.0, nx_ - 1.0));
}
int PointGrid::cell_y(double y) const {
  return static_cast<int>(std::clamp(std::floor((y - lo_.y()) / cell_), 0.0, ny_ - 1.0));
}

std::vector<int> PointGrid::ids_by_cell() const {
  std::vector<int> out;
  out.reserve(ids_.size());
  for (std::size_t c = 0; c < count_.size(); ++c) {
    out.insert(out.end(), ids_.begin() + start_[c], ids_.begin() + start_[c] + count_[c]);
  }
  return out;
}

void PointGrid::forget(int id) {
  const std::size_t c = cell_of(points_[id]);
  const std::uint32_t first = start_[c], last = start_[c] + count_[c];
  for (std::uint32_t i = first; i < last; ++i) {
    if (ids_[i] == id) {
      std::swap(ids_[i], ids_[last - 1]);
      --count_[c];
      return;
    }
  }
}

}  // namespace strand::post
