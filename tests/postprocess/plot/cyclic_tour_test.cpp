// The ring tour answers every query exactly as a plain array tour doing the same moves.
#include "postprocess/plot/cyclic_tour.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace strand::post {
namespace {

using slicer::Vec2;

// The reference: entries 2 * stroke + turned round, per position, moved the obvious way.
struct ArrayTour {
  std::vector<int> order;
  void reverse_block(int i, int j) {
    std::reverse(order.begin() + i, order.begin() + j + 1);
    for (int k = i; k <= j; ++k) order[k] ^= 1;
  }
  void shift(int m, int to) {
    const int e = order[m];
    order.erase(order.begin() + m);
    order.insert(order.begin() + to, e);
  }
};

void expect_same(const CyclicTour& t, const ArrayTour& a) {
  ASSERT_EQ(t.size(), static_cast<int>(a.order.size()));
  for (int p = 0; p < t.size(); ++p) {
    ASSERT_EQ(t.in(p), a.order[p]) << "position " << p;
    ASSERT_EQ(t.out(p), a.order[p] ^ 1);
    ASSERT_EQ(t.stroke_at(p), a.order[p] >> 1);
    ASSERT_EQ(t.pos_of(a.order[p] >> 1), p);
    ASSERT_EQ(t.reversed(a.order[p] >> 1), (a.order[p] & 1) != 0);
  }
}

CyclicTour random_tour(int n, std::mt19937& rng, ArrayTour& a) {
  std::uniform_real_distribution<double> u(0.0, 100.0);
  std::vector<Vec2> ends(2 * n);
  for (auto& e : ends) e = Vec2(u(rng), u(rng));
  std::vector<char> reversed(n);
  a.order.resize(n);
  for (int s = 0; s < n; ++s) {
    reversed[s] = static_cast<char>(rng() % 2);
    a.order[s] = 2 * s + reversed[s];
  }
  return CyclicTour(std::move(ends), Vec2(-1, -1), reversed);
}

class RingTour : public ::testing::TestWithParam<int> {};

// Long and short moves alike, so both sides of the ring are taken and the start travels.
TEST_P(RingTour, MovesMatchAPlainArray) {
  const int n = GetParam();
  std::mt19937 rng(static_cast<unsigned>(n));
  ArrayTour a;
  CyclicTour t = random_tour(n, rng, a);
  expect_same(t, a);
  std::uniform_int_distribution<int> pos(0, n - 1);
  for (int step = 0; step < 400; ++step) {
    int i = pos(rng), j = pos(rng);
    if (step % 2 == 0) {
      if (i > j) std::swap(i, j);
      t.reverse_block(i, j);
      a.reverse_block(i, j);
    } else {
      t.shift(i, j);
      a.shift(i, j);
    }
    expect_same(t, a);
  }
}

INSTANTIATE_TEST_SUITE_P(Sizes, RingTour, ::testing::Values(1, 2, 3, 4, 7, 50, 301));

TEST(RingTour, EdgesStartAtTheStartPointAndLengthSumsThem) {
  // Stroke 0 from (1,0) to (2,0), stroke 1 from (5,0) to (3,0); start at the origin.
  CyclicTour t({Vec2(1, 0), Vec2(2, 0), Vec2(5, 0), Vec2(3, 0)}, Vec2(0, 0), {0, 0});
  EXPECT_DOUBLE_EQ(t.edge(-1), 1.0);
  EXPECT_DOUBLE_EQ(t.edge(0), 3.0);
  EXPECT_DOUBLE_EQ(t.edge(1), 0.0);
  t.reverse_block(1, 1);  // stroke 1 now from (3,0): one unit from stroke 0's end
  EXPECT_DOUBLE_EQ(t.length(), 2.0);
  t.reverse_block(0, 1);  // stroke 1 first, from (5,0), then stroke 0 from (2,0)
  EXPECT_EQ(t.stroke_at(0), 1);
  EXPECT_DOUBLE_EQ(t.length(), 5.0 + 1.0);
}

}  // namespace
}  // namespace strand::post
