// An open pen tour stored as a cycle, so a block reversal or a single-stroke shift touches the
// shorter side: cost min(k, n - k) for a move over k strokes instead of k (a nearest-neighbour
// tour's 2-opt fixes are often half the tour long).
#pragma once

#include <vector>

#include "slicer/geometry.h"

namespace strand::post {

// Strokes 0..n-1 with fixed start point, each drawn one way round. The caller sees positions
// 0..n-1 (and -1 for the start); inside, the start is stroke n on a ring of n + 1 slots, read
// from its slot in direction dir_, entries flipped when dir_ < 0. Reversing the complement of
// a block and then reading the ring the other way gives the same tour as reversing the block,
// so every query answers exactly as for a plain array that reversed the block itself.
class CyclicTour {
 public:
  // Strokes in label order, `reversed` giving each one's way round; ends[2s] is the start of
  // stroke s, ends[2s + 1] its end.
  CyclicTour(std::vector<slicer::Vec2> ends, const slicer::Vec2& start,
             const std::vector<char>& reversed);

  int size() const { return n_; }
  // Entries are 2 * stroke + 1 when the stroke is drawn turned round: its entry endpoint.
  int in(int p) const { return order_[slot(p)] ^ flip_; }
  int out(int p) const { return in(p) ^ 1; }
  int stroke_at(int p) const { return order_[slot(p)] >> 1; }
  int pos_of(int stroke) const {
    int c = dir_ > 0 ? pos_[stroke] - base_ : base_ - pos_[stroke];
    if (c < 0) c += ring_;
    return c - 1;
  }
  bool reversed(int stroke) const { return ((order_[pos_[stroke]] ^ flip_) & 1) != 0; }
  slicer::Vec2 out_point(int p) const { return p < 0 ? start_ : ends_[out(p)]; }
  slicer::Vec2 in_point(int p) const { return ends_[in(p)]; }
  slicer::Vec2 ends_point(int e) const { return ends_[e]; }
  const std::vector<slicer::Vec2>& ends() const { return ends_; }
  // Cost of the edge from position p to p + 1 (p = -1: from the start; p + 1 = size: none).
  double edge(int p) const { return p + 1 >= n_ ? 0.0 : (out_point(p) - in_point(p + 1)).norm(); }
  double length() const;

  // Reverses positions i..j (0 <= i <= j < size) and turns each of those strokes round.
  void reverse_block(int i, int j);
  // Moves the stroke at position m to position to, keeping its direction; the strokes between
  // shift by one.
  void shift(int m, int to);

 private:
  // The slot of position p (-1 <= p <= size; size is the start again, one lap on).
  int slot(int p) const {
    int s = dir_ > 0 ? base_ + p + 1 : base_ - p - 1;
    if (s >= ring_) s -= ring_;
    if (s < 0) s += ring_;
    return s;
  }
  int next_slot(int s, int step) const {
    s += step;
    return s == ring_ ? 0 : (s < 0 ? ring_ - 1 : s);
  }
  // Reverses and turns round the `count` entries from slot `first` on, upward around the ring.
  void reverse_slots(int first, int count);
  // Moves the entry at slot `from` `count` slots in direction `step`, the entries passed
  // sliding one slot back.
  void slide(int from, int count, int step);

  std::vector<slicer::Vec2> ends_;
  slicer::Vec2 start_;
  int n_ = 0;
  int ring_ = 1;            // n_ + 1 slots
  std::vector<int> order_;  // per slot: 2 * stroke + turned round (the start: 2n + 1)
  std::vector<int> pos_;    // per stroke (the start is stroke n): its slot
  int base_ = 0;            // the start's slot
  int dir_ = 1;             // the direction the tour is read in (+1 or -1)
  int flip_ = 0;            // 1 when dir_ < 0: entries read turned round
};

}  // namespace strand::post
