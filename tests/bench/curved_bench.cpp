// The thesis cylinder specimen (samples/missing-rib-cylinder.json) end to end on the robot
// cell: generation, pose planning, reach/turn/IK checks and every writer; then its parts
// alone (planning, inverse kinematics over the program, the pose CSV check).
#include <benchmark/benchmark.h>

#include "machines/joint_analysis.h"
#include "machines/pose_csv.h"
#include "patterns/registry.h"
#include "postprocess/inspect/pose_check.h"
#include "postprocess/plan/produce_curved.h"

namespace {

using namespace strand;

// The sample's parameters (kept in step with samples/missing-rib-cylinder.json).
const nlohmann::json kParams = {{"nozzle", 1.2}, {"rib", 6},  {"angle", 20},
                                {"rows", 4},     {"cols", 8}, {"layers", 3}};
const slicer::SubstrateSpec kCylinder{"cylinder", 20.0, 80.0, slicer::Wrap::Patch,
                                      slicer::ArcLengthAt::Surface};

slicer::Toolpath thesis_pattern() {
  const auto* g = patterns::find_generator("missing-rib");
  return g->generate(slicer::resolve_params(g->table(), kParams));
}

const machines::MachineProfile& cell() {
  static const auto m = machines::load_profile("kuka-iiwa14-wasp-cylinder");
  return m;
}

void BM_ThesisCylinderEndToEnd(benchmark::State& state) {
  std::size_t poses = 0;
  for (auto _ : state) {
    const auto out = post::produce_curved(thesis_pattern(), kCylinder, cell(), 0.01, "bench.csv");
    poses = out.program.points.size();
    benchmark::DoNotOptimize(out.files.data());
  }
  state.counters["poses"] = static_cast<double>(poses);
  state.counters["us_per_pose"] =
      benchmark::Counter(static_cast<double>(poses) * state.iterations(),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_ThesisCylinderEndToEnd)->Unit(benchmark::kMillisecond);

void BM_ThesisCylinderJointsAlongThePath(benchmark::State& state) {
  const auto out = post::produce_curved(thesis_pattern(), kCylinder, cell(), 0.01, "bench.csv");
  const auto arm = machines::lbr_iiwa_14_r820(cell().robot);
  for (auto _ : state) {
    const auto r = machines::analyse_joints(arm, cell().robot, out.program.points);
    benchmark::DoNotOptimize(r.max_rad.data());
  }
  state.counters["poses"] = static_cast<double>(out.program.points.size());
}
BENCHMARK(BM_ThesisCylinderJointsAlongThePath)->Unit(benchmark::kMillisecond);

void BM_ThesisCylinderCsvCheck(benchmark::State& state) {
  const auto out = post::produce_curved(thesis_pattern(), kCylinder, cell(), 0.01, "bench.csv");
  const std::string& csv = out.files.front().second;
  for (auto _ : state) {
    const auto r = post::check_pose_csv(csv, "bench.csv", cell());
    benchmark::DoNotOptimize(r.rows);
  }
  state.counters["csv_bytes"] = static_cast<double>(csv.size());
}
BENCHMARK(BM_ThesisCylinderCsvCheck)->Unit(benchmark::kMillisecond);

}  // namespace
