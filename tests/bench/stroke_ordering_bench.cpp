// Ordering 100,000 random pen strokes (greedy start tour + 2-opt/Or-opt) must take < 1 s.
#include <benchmark/benchmark.h>

#include <random>

#include "postprocess/plot/stroke_ordering.h"

namespace {

std::vector<strand::slicer::Stroke> random_strokes(int n) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(0.0, 420.0), v(-3.0, 3.0);
  std::vector<strand::slicer::Stroke> out;
  for (int i = 0; i < n; ++i) {
    strand::slicer::Stroke s;
    s.start_mm = strand::slicer::Vec2(u(rng), u(rng) * 297.0 / 420.0);
    s.segments.push_back(strand::slicer::line_to(s.start_mm + strand::slicer::Vec2(v(rng), v(rng)),
                                                 strand::slicer::Feature::Pen));
    s.reversible = true;
    out.push_back(s);
  }
  return out;
}

void BM_OrderStrokes(benchmark::State& state) {
  const auto strokes = random_strokes(static_cast<int>(state.range(0)));
  strand::post::OrderOptions o;
  double before = strand::post::pen_up_travel(strokes, o.start_mm, nullptr).first, after = 0.0;
  for (auto _ : state) {
    const auto out = strand::post::order_strokes(strokes, o);
    after = strand::post::pen_up_travel(out, o.start_mm, nullptr).first;
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["pen_up_before_mm"] = before;
  state.counters["pen_up_after_mm"] = after;
}
BENCHMARK(BM_OrderStrokes)->Arg(100000)->Unit(benchmark::kMillisecond);

void BM_StartTourOnly(benchmark::State& state) {
  const auto strokes = random_strokes(static_cast<int>(state.range(0)));
  strand::post::OrderOptions o;
  o.evaluations_per_stroke = 0;
  double after = 0.0;
  for (auto _ : state) {
    const auto out = strand::post::order_strokes(strokes, o);
    after = strand::post::pen_up_travel(out, o.start_mm, nullptr).first;
  }
  state.counters["pen_up_after_mm"] = after;
}
BENCHMARK(BM_StartTourOnly)->Arg(100000)->Unit(benchmark::kMillisecond);

}  // namespace
