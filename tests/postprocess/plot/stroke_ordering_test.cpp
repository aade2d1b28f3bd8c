// Ordering keeps every stroke exactly once and beats the input order; merging joins ends.
#include "postprocess/plot/stroke_ordering.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>
#include <tuple>

namespace strand::post {
namespace {

using slicer::Stroke;
using slicer::Vec2;

std::vector<Stroke> random_strokes(int n, unsigned seed, int pens = 1) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 300.0), v(-5.0, 5.0);
  std::vector<Stroke> out;
  for (int i = 0; i < n; ++i) {
    Stroke s;
    s.start_mm = Vec2(u(rng), u(rng));
    s.segments.push_back(slicer::line_to(s.start_mm + Vec2(v(rng), v(rng)), slicer::Feature::Pen));
    s.reversible = true;
    s.tool = i % pens;
    out.push_back(s);
  }
  return out;
}

// A stroke's identity regardless of direction: its two endpoints, sorted.
std::vector<std::array<double, 5>> identities(const std::vector<Stroke>& strokes) {
  std::vector<std::array<double, 5>> ids;
  for (const auto& s : strokes) {
    Vec2 a = s.start_mm, b = s.end_mm();
    if (std::tie(a.x(), a.y()) > std::tie(b.x(), b.y())) std::swap(a, b);
    ids.push_back({a.x(), a.y(), b.x(), b.y(), static_cast<double>(s.tool)});
  }
  std::sort(ids.begin(), ids.end());
  return ids;
}

class Ordering : public ::testing::TestWithParam<unsigned> {};

TEST_P(Ordering, KeepsEveryStrokeOnceAndCutsPenUpTravel) {
  const auto in = random_strokes(3000, GetParam(), 3);
  OrderOptions o;
  const auto out = order_strokes(in, o);
  EXPECT_EQ(identities(out), identities(in));
  const double before = pen_up_travel(in, o.start_mm, nullptr).first;
  const double after = pen_up_travel(out, o.start_mm, nullptr).first;
  EXPECT_LT(after, 0.2 * before);
  for (std::size_t i = 1; i < out.size(); ++i) EXPECT_LE(out[i - 1].tool, out[i].tool);
}

TEST_P(Ordering, ImprovementBeatsPlainNearestNeighbour) {
  const auto in = random_strokes(3000, GetParam());
  OrderOptions greedy;
  greedy.evaluations_per_stroke = 0;
  const double nn = pen_up_travel(order_strokes(in, greedy), greedy.start_mm, nullptr).first;
  const double improved = pen_up_travel(order_strokes(in, OrderOptions{}), greedy.start_mm, nullptr).first;
  EXPECT_LT(improved, 0.95 * nn);
}

INSTANTIATE_TEST_SUITE_P(Seeds, Ordering, ::testing::Values(1u, 2u, 3u));

TEST(Ordering, IsDeterministic) {
  const auto in = random_strokes(2000, 7);
  EXPECT_EQ(order_strokes(in, OrderOptions{}), order_strokes(in, OrderOptions{}));
}

TEST(Ordering, MetricSpaceDrivesTheChoice) {
  // Two candidates at the same paper distance; the metric makes y travel 10x as costly.
  Stroke a, b;
  a.start_mm = Vec2(0, 10);
  a.segments.push_back(slicer::line_to(Vec2(0, 11), slicer::Feature::Pen));
  b.start_mm = Vec2(10, 0);
  b.segments.push_back(slicer::line_to(Vec2(11, 0), slicer::Feature::Pen));
  a.reversible = b.reversible = true;
  OrderOptions o;
  o.metric = [](const Vec2& p) { return Vec2(p.x(), 10 * p.y()); };
  const auto out = order_strokes({a, b}, o);
  EXPECT_EQ(out[0].start_mm, b.start_mm);
}

TEST(Ordering, TurnsStrokesRoundExactlyAsReversedDoes) {
  // Arcs and lines: a stroke drawn the other way must equal slicer::reversed of the input,
  // and only reversible ones are turned round.
  std::vector<Stroke> in;
  for (int i = 0; i < 200; ++i) {
    Stroke s;
    s.start_mm = Vec2(3.0 * (i % 20), 7.0 * (i / 20));
    s.segments.push_back(slicer::line_to(s.start_mm + Vec2(1, 0), slicer::Feature::Pen));
    s.segments.push_back(slicer::arc_to(s.start_mm + Vec2(2, 1), s.start_mm + Vec2(1, 1),
                                        i % 2 == 0, slicer::Feature::Pen));
    s.reversible = i % 3 != 0;
    in.push_back(s);
  }
  int turned = 0;
  for (const auto& s : order_strokes(in, OrderOptions{})) {
    const bool found = std::any_of(in.begin(), in.end(), [&](const Stroke& t) {
      if (t == s) return true;
      if (slicer::reversed(t) == s) {
        EXPECT_TRUE(t.reversible);
        return ++turned, true;
      }
      return false;
    });
    EXPECT_TRUE(found);
  }
  EXPECT_GT(turned, 0);
}

TEST(Merging, JoinsStrokesWhoseEndsMeetInEitherDirection) {
  Stroke a, b, c;
  a.start_mm = Vec2(0, 0);
  a.segments.push_back(slicer::line_to(Vec2(10, 0), slicer::Feature::Pen));
  b.start_mm = Vec2(20, 0);  // reversed, it continues a
  b.segments.push_back(slicer::line_to(Vec2(10, 0.001), slicer::Feature::Pen));
  c.start_mm = Vec2(-5, 0);  // its end meets a's start
  c.segments.push_back(slicer::line_to(Vec2(0, 0), slicer::Feature::Pen));
  a.reversible = b.reversible = c.reversible = true;
  const auto out = merge_touching({a, b, c}, 0.01);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_NEAR(slicer::stroke_length(out[0]), 10 + 10 + 5 + 0.001, 1e-6);
  EXPECT_EQ(merge_touching({a, b, c}, 0.0001).size(), 2u);  // the 1 µm gap is now too wide
}

}  // namespace
}  // namespace strand::post
