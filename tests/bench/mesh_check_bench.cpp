// The mesh check `strand slice` and `strand mesh` run before anything else (slicer/mesh_check.h):
// welding coincident vertices, edge use, touching vertices, self-intersections and orientation,
// on a closed 1,000,000-triangle torus. Peak memory of the process is reported as a counter.
// Two tori overlapping (self-intersecting, as overlapping shells are): slicing
// stops at the first crossing, `strand mesh` counts every pair.
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include "slicer/mesh_check.h"
#include "slicer/mesh_io.h"
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

// 2 x 200,000 triangles, the second torus 20 mm beside the first: their tubes cut each other twice.
strand::slicer::Mesh overlapping_tori() {
  using namespace strand;
  const slicer::Mesh a = testing::torus_mesh(30.0, 8.0, 500, 200);
  slicer::Mesh b = a;
  for (slicer::Vec3& v : b.vertices_mm) v.x() += 20.0;
  return slicer::merge_meshes({a, b});
}

void BM_PrepareOverlappingTori(benchmark::State& state) {  // what `strand slice` runs
  using namespace strand;
  const slicer::Mesh tori = overlapping_tori();
  bool found = false;
  for (auto _ : state) {
    const slicer::PreparedMesh p =
        slicer::prepare_mesh(tori, slicer::PrepareOptions{}, "mesh = tori");
    found = p.before.self_intersecting;
    benchmark::DoNotOptimize(p.mesh.triangles.data());
  }
  if (!found) state.SkipWithError("the tori should cut each other");
  state.counters["triangles"] = static_cast<double>(tori.triangles.size());
}
BENCHMARK(BM_PrepareOverlappingTori)->Unit(benchmark::kMillisecond)->Iterations(3);

void BM_CountOverlappingToriCrossings(benchmark::State& state) {  // what `strand mesh` runs
  using namespace strand;
  const slicer::Mesh tori = overlapping_tori();
  std::size_t pairs = 0;
  for (auto _ : state) pairs = slicer::check_mesh(tori).self_intersections;
  if (pairs == 0) state.SkipWithError("the tori should cut each other");
  state.counters["pairs"] = static_cast<double>(pairs);
}
BENCHMARK(BM_CountOverlappingToriCrossings)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace
