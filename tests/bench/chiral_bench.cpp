// Chiral specimens from parameters to G-code text: the thesis samples, a large tetrachiral
// lattice and wrapped sleeves to watch the Euler circuit's merging cost (issue 3: the
// sample jobs must run in well under a second).
#include <benchmark/benchmark.h>

#include "machines/profile.h"
#include "patterns/hexachiral.h"
#include "patterns/registry.h"
#include "patterns/tetrachiral.h"
#include "postprocess/plan/produce.h"

namespace {

void run(benchmark::State& state, const strand::slicer::ParamTable& table,
         strand::slicer::Toolpath (*make)(const nlohmann::json&), const nlohmann::json& given) {
  using namespace strand;
  const auto values = slicer::resolve_params(table, given);
  const auto machine = machines::load_profile("deltawasp-2040-clay");
  for (auto _ : state) {
    const auto t = make(values);
    auto out = post::produce(t, machine, post::plan_options_from(t, 0.01), "bench.gcode");
    benchmark::DoNotOptimize(out.gcode.data());
  }
}

void BM_ThesisTetrachiralToGcode(benchmark::State& state) {
  run(state, strand::patterns::tetrachiral_table(), strand::patterns::find_generator("tetrachiral")->generate,
      {{"nozzle", 0.5}, {"cell", 10}, {"cols", 2}, {"rows", 6}, {"layers", 5}, {"grip", 10}});
}
BENCHMARK(BM_ThesisTetrachiralToGcode)->Unit(benchmark::kMillisecond);

void BM_ThesisHexachiralToGcode(benchmark::State& state) {
  run(state, strand::patterns::hexachiral_table(), strand::patterns::find_generator("hexachiral")->generate,
      {{"nozzle", 0.4}, {"cell", 5.3}, {"cols", 4}, {"rows", 10}, {"layers", 5}, {"grip", 10}});
}
BENCHMARK(BM_ThesisHexachiralToGcode)->Unit(benchmark::kMillisecond);

void BM_TetrachiralLattice24x24OneLayer(benchmark::State& state) {
  run(state, strand::patterns::tetrachiral_table(), strand::patterns::find_generator("tetrachiral")->generate,
      {{"nozzle", 0.4}, {"cell", 5}, {"cols", 24}, {"rows", 24}, {"layers", 1}, {"grip", 5}});
}
BENCHMARK(BM_TetrachiralLattice24x24OneLayer)->Unit(benchmark::kMillisecond);

// The periodic variants (`--wrap full`) alone, toolpath only: a sleeve of N x N cells
// round a cylinder. The Euler circuit's sure merges keep this about linear in the nodes
// (before them a hexachiral 80 x 80 took 7 s).
void wrapped(benchmark::State& state, const char* name, double cell_mm) {
  using namespace strand;
  const auto* g = patterns::find_generator(name);
  const int n = static_cast<int>(state.range(0));
  const auto values = slicer::resolve_params(
      g->table(), {{"nozzle", 0.5}, {"cell", cell_mm}, {"rows", n}, {"layers", 1}, {"grip", 5}});
  for (auto _ : state) {
    const auto t = g->generate_wrapped(values, cell_mm * n);
    benchmark::DoNotOptimize(t.layers.data());
  }
  state.SetComplexityN(n * n);
}
void BM_WrappedTetrachiralSleeve(benchmark::State& state) { wrapped(state, "tetrachiral", 10); }
BENCHMARK(BM_WrappedTetrachiralSleeve)->Arg(20)->Arg(80)->Unit(benchmark::kMillisecond);
void BM_WrappedHexachiralSleeve(benchmark::State& state) { wrapped(state, "hexachiral", 10); }
BENCHMARK(BM_WrappedHexachiralSleeve)->Arg(20)->Arg(80)->Unit(benchmark::kMillisecond);

}  // namespace
