// The mesh check `strand slice` and `strand mesh` run before anything else (slicer/mesh_check.h):
// welding coincident vertices, edge use, touching vertices, self-intersections and orientation,
// on a closed 1,000,000-triangle torus. Peak memory of the process is reported as a counter.
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include "slicer/mesh_check.h"
#include "tests/support/mesh_shapes.h"

namespace {

void BM_CheckTorusMillionTriangles(benchmark::State& state) {
  using namespace strand;
  const slicer::Mesh torus = testing::torus_mesh(45.0, 30.0, 1000, 500);  // 1,000,000 triangles
  bool ok = false;
  for (auto _ : state) {
    const slicer::PreparedMesh p = slicer::prepare_mesh(torus, false, "mesh = torus");
    ok = p.before.ok();
    benchmark::DoNotOptimize(p.mesh.triangles.data());
  }
  if (!ok) state.SkipWithError("the torus should be sound");
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  state.counters["triangles"] = static_cast<double>(torus.triangles.size());
  state.counters["peak_RSS_MB"] = static_cast<double>(usage.ru_maxrss) / 1024.0;
}
BENCHMARK(BM_CheckTorusMillionTriangles)->Unit(benchmark::kMillisecond)->Iterations(2);

}  // namespace
