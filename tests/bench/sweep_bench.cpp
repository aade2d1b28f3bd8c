// A 100-point scaffold sweep (10 nozzles x 10 gaps, 20 x 20 x 5 mm) into a fresh directory:
// generate, plan, emit, check, thumbnail, manifest and index. Target (issue 6): seconds.
// Argument: worker threads; the second variant skips the thumbnails.
#include <benchmark/benchmark.h>

#include <filesystem>

#include "jobs/sweep_runner.h"

namespace {

const nlohmann::json kSweep = {
    {"job", {{"generator", "scaffold"}, {"params", {{"size", "20x20"}, {"height", 5}}}}},
    {"vary", {{"nozzle", {{"from", 0.4}, {"to", 0.85}, {"step", 0.05}}},
              {"gap", {{"from", 0.9}, {"to", 1.8}, {"step", 0.1}}}}}};

void run(benchmark::State& state, bool previews) {
  using namespace strand::jobs;
  const SweepSpec spec = sweep_spec_from_json(kSweep);
  const auto dir = std::filesystem::temp_directory_path() / "strand-bench-sweep";
  std::size_t points = 0;
  for (auto _ : state) {
    state.PauseTiming();
    std::filesystem::remove_all(dir);
    state.ResumeTiming();
    SweepOptions o;
    o.dir = dir.string();
    o.jobs = static_cast<int>(state.range(0));
    o.previews = previews;
    const SweepResult r = run_sweep(spec, kSweep, o, nullptr);
    points = r.ran;
    benchmark::DoNotOptimize(r.manifest);
  }
  state.counters["points"] = static_cast<double>(points);
  std::filesystem::remove_all(dir);
}

void BM_Sweep100Points(benchmark::State& state) { run(state, true); }
void BM_Sweep100PointsNoPreviews(benchmark::State& state) { run(state, false); }
BENCHMARK(BM_Sweep100Points)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Sweep100PointsNoPreviews)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
