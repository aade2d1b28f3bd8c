// Missing-rib and re-entrant generators: the sample jobs from parameters to G-code text, and
// the non-crossing circuit on a large missing-rib network (generation only, 100 x 100 cells).
#include <benchmark/benchmark.h>

#include "machines/profile.h"
#include "patterns/missing_rib.h"
#include "patterns/reentrant.h"
#include "patterns/registry.h"
#include "postprocess/plan/produce.h"

namespace {

using namespace strand;

template <class Table, class Generate>
void to_gcode(benchmark::State& state, Table table, Generate generate, const nlohmann::json& given) {
  const auto values = slicer::resolve_params(table(), given);
  const auto machine = machines::load_profile("deltawasp-2040-clay");
  for (auto _ : state) {
    const auto t = generate(values);
    auto out = post::produce(t, machine, post::plan_options_from(t, 0.01), "bench.gcode");
    benchmark::DoNotOptimize(out.gcode.data());
  }
}

void BM_MissingRibSampleToGcode(benchmark::State& state) {
  to_gcode(state, &patterns::missing_rib_table, patterns::find_generator("missing-rib")->generate,
           {{"nozzle", 0.6}, {"rib", 5}, {"angle", 20}, {"rows", 6}, {"cols", 6}, {"layers", 3}});
}
BENCHMARK(BM_MissingRibSampleToGcode)->Unit(benchmark::kMillisecond);

void BM_ReentrantSampleToGcode(benchmark::State& state) {
  to_gcode(state, &patterns::reentrant_table, patterns::find_generator("reentrant")->generate,
           {{"nozzle", 0.84}, {"cell-width", 8}, {"cell-height", 8}, {"angle", 20}, {"rows", 6}, {"cols", 5}, {"height", 5}});
}
BENCHMARK(BM_ReentrantSampleToGcode)->Unit(benchmark::kMillisecond);

void BM_MissingRibLargeNetworkOneLayer(benchmark::State& state) {
  patterns::MissingRibParams p;
  p.nozzle_mm = 0.5;
  p.rib_mm = 1.5;
  p.rows = p.cols = 100;
  p.layers = 1;
  p.layer_height_mm = 0.4;
  for (auto _ : state) {
    const auto t = patterns::generate_missing_rib(p);
    benchmark::DoNotOptimize(t.layers.data());
  }
}
BENCHMARK(BM_MissingRibLargeNetworkOneLayer)->Unit(benchmark::kMillisecond);

}  // namespace
