// Candidate lists for tour improvement: the k nearest other-stroke endpoints of each endpoint.
#pragma once

#include <cstdint>
#include <vector>

#include "slicer/geometry.h"

namespace strand::post {

// Flat lists: endpoint 2s is the start of stroke s, 2s + 1 its end; each list holds the k
// nearest endpoints of other strokes, nearest first (ties by id).
class NearLists {
 public:
  NearLists(const std::vector<slicer::Vec2>& ends, int k);
  // The same lists with stroke s renamed label[s] (endpoint 2s + i -> 2 label[s] + i).
  NearLists relabelled(const std::vector<int>& label) const;

  struct Range {
    const int* b;
    const int* e;
    const int* begin() const { return b; }
    const int* end() const { return e; }
  };
  Range operator[](int e) const {
    const int* b = ids_.data() + static_cast<std::size_t>(e) * k_;
    return {b, b + count_[static_cast<std::size_t>(e)]};
  }

 private:
  NearLists() = default;
  int k_ = 0;
  std::vector<int> ids_;
  std::vector<std::uint8_t> count_;
};

}  // namespace strand::post
