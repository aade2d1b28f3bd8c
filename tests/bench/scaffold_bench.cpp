// Thesis scaffold (d 0.84, gap 1.6, 36x36x13 mm) from parameters to G-code text.
// Target (issue 2): well under 50 ms.
#include <benchmark/benchmark.h>

#include "machines/profile.h"
#include "patterns/scaffold.h"
#include "patterns/registry.h"
#include "postprocess/plan/produce.h"

namespace {

void BM_ThesisScaffoldToGcode(benchmark::State& state) {
  using namespace strand;
  const auto values = slicer::resolve_params(
      patterns::scaffold_table(), {{"nozzle", 0.84}, {"gap", 1.6}, {"size", "36x36"}, {"height", 13}});
  const auto machine = machines::load_profile("deltawasp-2040-clay");
  for (auto _ : state) {
    const auto t = patterns::find_generator("scaffold")->generate(values);
    auto out = post::produce(t, machine, post::plan_options_from(t, 0.01), "bench.gcode");
    benchmark::DoNotOptimize(out.gcode.data());
  }
}
BENCHMARK(BM_ThesisScaffoldToGcode)->Unit(benchmark::kMillisecond);

}  // namespace
