// `strand slice` on a 100k-triangle torus (R 45 mm, tube 30 mm, 60 mm tall) into 200
// layers of the scaffold (nozzle 0.4 mm, pitch 2 mm, h 0.3 mm): read, check, slice, fill,
// plan and emit, as the CLI does. Peak memory of the process is reported as a counter.
// Side by side with PrusaSlicer: tests/bench/slice_vs_prusaslicer.sh.
#include <benchmark/benchmark.h>
#include <sys/resource.h>
#include <unistd.h>

#include <filesystem>

#include "jobs/slice_job.h"
#include "tests/support/mesh_shapes.h"

namespace {

void BM_SliceTorus100kInto200Layers(benchmark::State& state) {
  using namespace strand;
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("strand-bench-torus-" + std::to_string(getpid()) + ".stl"))
                               .string();
  const slicer::Mesh torus = testing::torus_mesh(45.0, 30.0, 500, 100);  // 100,000 triangles
  testing::write_binary_stl(torus, path);
  jobs::SliceSettings s;
  s.part = path;
  s.pattern_values = {{"nozzle", 0.4}, {"pitch", 2.0}, {"layer-height", 0.3}};
  s.machine = "marlin-xyz-200";
  std::size_t layers = 0, bytes = 0;
  for (auto _ : state) {
    const jobs::SliceResult r = jobs::produce_slice(s);
    layers = r.toolpath.derived.at("layers").get<std::size_t>();
    bytes = r.produced.gcode.size();
    benchmark::DoNotOptimize(r.produced.gcode.data());
  }
  std::filesystem::remove(path);
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  state.counters["triangles"] = static_cast<double>(torus.triangles.size());
  state.counters["layers"] = static_cast<double>(layers);
  state.counters["gcode_MB"] = static_cast<double>(bytes) / 1e6;
  state.counters["peak_RSS_MB"] = static_cast<double>(usage.ru_maxrss) / 1024.0;
}
BENCHMARK(BM_SliceTorus100kInto200Layers)->Unit(benchmark::kMillisecond)->Iterations(2);

}  // namespace
