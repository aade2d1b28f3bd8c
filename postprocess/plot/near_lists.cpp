// k-nearest candidate lists over a point grid.
#include "postprocess/plot/near_lists.h"

#include <algorithm>

#include "postprocess/plot/point_grid.h"

namespace strand::post {

NearLists::NearLists(const std::vector<slicer::Vec2>& ends, int k)
    : k_(std::clamp(k, 0, PointGrid::kMaxK)) {
  const PointGrid grid(ends);
  ids_.resize(ends.size() * static_cast<std::size_t>(k_));
  count_.resize(ends.size());
  for (std::size_t e = 0; e < ends.size(); ++e) {
    const int s = static_cast<int>(e / 2);
    count_[e] = static_cast<std::uint8_t>(grid.k_nearest(
        ends[e], k_, [s](int id) { return id / 2 == s; }, &ids_[e * k_]));
  }
}

NearLists NearLists::relabelled(const std::vector<int>& label) const {
  NearLists out;
  out.k_ = k_;
  out.ids_.resize(ids_.size());
  out.count_.resize(count_.size());
  const auto k = static_cast<std::size_t>(k_);
  for (std::size_t e = 0; e < count_.size(); ++e) {
    const std::size_t to = 2 * static_cast<std::size_t>(label[e / 2]) + e % 2;
    out.count_[to] = count_[e];
    for (std::size_t i = 0; i < count_[e]; ++i) {
      const int id = ids_[e * k + i];
      out.ids_[to * k + i] = 2 * label[static_cast<std::size_t>(id / 2)] + id % 2;
    }
  }
  return out;
}

}  // namespace strand::post
