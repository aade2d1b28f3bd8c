// Ring moves of the pen tour: reversals and shifts done on whichever side of the ring is shorter.
#include "postprocess/plot/cyclic_tour.h"

#include <algorithm>
#include <utility>

namespace strand::post {

CyclicTour::CyclicTour(std::vector<slicer::Vec2> ends, const slicer::Vec2& start,
                       const std::vector<char>& reversed)
    : ends_(std::move(ends)),
      start_(start),
      n_(static_cast<int>(ends_.size() / 2)),
      ring_(n_ + 1),
      order_(static_cast<std::size_t>(ring_)),
      pos_(static_cast<std::size_t>(ring_)) {
  order_[0] = 2 * n_ + 1;  // the start, entered by its free end and left from start_
  pos_[n_] = 0;
  for (int p = 0; p < n_; ++p) {
    order_[p + 1] = 2 * p + (reversed[p] ? 1 : 0);
    pos_[p] = p + 1;
  }
}

double CyclicTour::length() const {
  double total = 0.0;
  for (int p = -1; p + 1 < n_; ++p) total += edge(p);
  return total;
}

void CyclicTour::reverse_slots(int first, int count) {
  int a = first, b = first + count - 1;
  if (b >= ring_) b -= ring_;
  // Pairs swapped in straight runs, a rising and b falling until one of them wraps.
  for (int pairs = count / 2; pairs > 0;) {
    const int run = std::min({pairs, ring_ - a, b + 1});
    for (const int end = a + run; a < end; ++a, --b) {
      const int oa = order_[a] ^ 1, ob = order_[b] ^ 1;
      order_[a] = ob;
      order_[b] = oa;
      pos_[ob >> 1] = a;
      pos_[oa >> 1] = b;
    }
    pairs -= run;
    if (a == ring_) a = 0;
    if (b < 0) b = ring_ - 1;
  }
  if (count % 2 == 1) order_[a] ^= 1;  // the middle entry stays, turned round
}

void CyclicTour::slide(int from, int count, int step) {
  const int moving = order_[from];
  int k = from;
  for (int c = 0; c < count; ++c) {
    const int next = next_slot(k, step);
    pos_[(order_[k] = order_[next]) >> 1] = k;
    k = next;
  }
  order_[k] = moving;
  pos_[moving >> 1] = k;
}

void CyclicTour::reverse_block(int i, int j) {
  const int count = j - i + 1;
  if (2 * count <= ring_) {
    reverse_slots(dir_ > 0 ? slot(i) : slot(j), count);
    return;
  }
  // The rest of the ring, start included (positions j + 1 .. size, which is -1, .. i - 1),
  // reversed; reading the ring the other way round then gives the block reversed.
  reverse_slots(dir_ > 0 ? slot(j + 1) : slot(i - 1), ring_ - count);
  base_ = pos_[n_];
  dir_ = -dir_;
  flip_ ^= 1;
}

void CyclicTour::shift(int m, int to) {
  if (m == to) return;
  const int distance = m < to ? to - m : m - to;
  const int step = m < to ? dir_ : -dir_;
  if (2 * distance <= ring_ - 1) {
    slide(slot(m), distance, step);
    return;
  }
  // Round the other side: past the strokes outside m..to and the start, which moves one slot.
  slide(slot(m), ring_ - 1 - distance, -step);
  base_ = pos_[n_];
}

}  // namespace strand::post
