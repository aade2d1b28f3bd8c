// The property of issue 37 item 2: every job the mesh planner writes passes `strand check`
// with the same profile (planner and check share slicer/mesh_row_rule.h); where it would not,
// the planner refuses with one line.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <functional>
#include <map>
#include <queue>
#include <random>
#include <set>
#include <string>

#include "machines/pose_csv.h"
#include "machines/profile.h"
#include "patterns/registry.h"
#include "postprocess/inspect/mesh_pose_check.h"
#include "postprocess/plan/produce_on_mesh.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"
#include "slicer/mesh_io.h"
#include "slicer/params.h"
#include "slicer/tolerances.h"
#include "tests/support/cli_runner.h"

namespace strand::post {
namespace {

using slicer::Mesh;
using slicer::Vec3;

// An open patch of `m`: the triangles whose corners lie within `radius` of vertex `seed`
// along the mesh's edges.
Mesh cut(const Mesh& m, int seed, double radius) {
  std::vector<std::set<int>> next(m.vertices_mm.size());
  for (const auto& t : m.triangles) {
    for (int k = 0; k < 3; ++k) {
      next[t[k]].insert(t[(k + 1) % 3]);
      next[t[(k + 1) % 3]].insert(t[k]);
    }
  }
  std::vector<double> d(m.vertices_mm.size(), 1e300);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> q;
  d[seed] = 0.0;
  q.push({0.0, seed});
  while (!q.empty()) {
    const auto [dist, i] = q.top();
    q.pop();
    if (dist > d[i] || dist > radius) continue;
    for (int j : next[i]) {
      const double nd = dist + (m.vertices_mm[i] - m.vertices_mm[j]).norm();
      if (nd < d[j]) d[j] = nd, q.push({nd, j});
    }
  }
  Mesh out;
  std::map<int, int> index;
  for (const auto& t : m.triangles) {
    if (d[t[0]] > radius || d[t[1]] > radius || d[t[2]] > radius) continue;
    std::array<int, 3> n{};
    for (int k = 0; k < 3; ++k) {
      const auto [it, fresh] = index.emplace(t[k], static_cast<int>(out.vertices_mm.size()));
      if (fresh) out.vertices_mm.push_back(m.vertices_mm[t[k]]);
      n[k] = it->second;
    }
    out.triangles.push_back(n);
  }
  return out;
}

std::string obj_text(const Mesh& m) {
  std::string s;
  char line[128];
  for (const Vec3& v : m.vertices_mm) {
    std::snprintf(line, sizeof line, "v %.4f %.4f %.4f\n", v.x(), v.y(), v.z());
    s += line;
  }
  for (const auto& t : m.triangles) {
    std::snprintf(line, sizeof line, "f %d %d %d\n", t[0] + 1, t[1] + 1, t[2] + 1);
    s += line;
  }
  return s;
}

struct Case {
  std::string mesh, arm;
  int seed = 0;
  double radius_mm = 0.0;
  int size_mm = 0, layers = 0;

  std::string text() const {
    return mesh + " cut " + slicer::short_number(radius_mm) + " mm around vertex " +
           std::to_string(seed) + ", scaffold " + std::to_string(size_mm) + " mm, " +
           std::to_string(layers) + " layer(s), " + arm;
  }
};

// Plans the case as `strand scaffold ... --substrate mesh` does, writes the CSV and its record,
// and checks the CSV as `strand check` does. Returns the planner's refusal, or "" when written.
std::string write_and_check(const Case& c, const std::string& dir, int n, PoseCheckReport& r) {
  const std::string stem = dir + "/p" + std::to_string(n);
  const Mesh whole =
      slicer::read_mesh_file(std::string(STRAND_SOURCE_DIR) + "/tests/data/" + c.mesh);
  slicer::write_file_atomic(stem + ".obj", obj_text(cut(whole, c.seed, c.radius_mm)));
  const machines::MachineProfile m = machines::load_profile(c.arm);
  const patterns::GeneratorSpec* g = patterns::find_generator("scaffold");
  const std::string size = std::to_string(c.size_mm) + "x" + std::to_string(c.size_mm);
  const slicer::Toolpath t = g->generate(slicer::resolve_params(
      g->table(), {{"nozzle", 0.8}, {"gap", 1.5}, {"size", size}, {"layers", c.layers}}));
  slicer::SubstrateSpec spec;
  spec.type = "mesh";
  spec.mesh_path = stem + ".obj";
  MeshJob job;
  try {
    job = plan_mesh_job(t, spec, m, slicer::kDefaultArcToleranceMm, stem + ".csv");
  } catch (const InputError& e) {
    return e.what();
  }
  const std::string csv = machines::write_pose_csv(job.plan.program);
  slicer::write_file_atomic(stem + ".csv", csv);
  slicer::write_file_atomic(job.record_file.first, job.record_file.second);
  const auto mesh = find_csv_mesh(stem + ".csv", "");
  EXPECT_TRUE(mesh.has_value());
  r = check_mesh_pose_csv(csv, stem + ".csv", m, *mesh);
  return "";
}

// Random patches (centre, radius), pattern sizes and layer counts of a coarse Stanford bunny,
// a coarse skull and a coarse saddle (tests/data/README.md) on every shipped arm that holds a
// mesh, seeded: no written job fails the check; refusals are one line and counted.
TEST(MeshPoseCheckProperty, EveryJobThePlannerWritesPassesTheCheck) {
  const std::vector<std::string> meshes = {"bunny-patch.obj", "skull-patch.obj",
                                           "saddle-patch.obj"};
  const std::vector<std::string> arms = {"kuka-iiwa14-wasp-cylinder", "ur10e-wasp-cylinder",
                                         "abb-irb1200-wasp-cylinder"};
#ifdef STRAND_SANITIZE_BUILD
  constexpr int kPerPair = 2;  // the same paths under ASan, where one case takes seconds
#else
  constexpr int kPerPair = 8;
#endif
  std::mt19937 rng(37);
  const std::string dir = testing::fresh_dir("mesh-row-property");
  int written = 0, refused = 0;
  for (const auto& name : meshes) {
    const int vertices = static_cast<int>(
        slicer::read_mesh_file(std::string(STRAND_SOURCE_DIR) + "/tests/data/" + name)
            .vertices_mm.size());
    for (const auto& arm : arms) {
      for (int k = 0; k < kPerPair; ++k) {
        Case c{name, arm};
        c.seed = std::uniform_int_distribution<int>(0, vertices - 1)(rng);
        c.radius_mm = std::uniform_int_distribution<int>(14, 26)(rng);
        c.size_mm = std::uniform_int_distribution<int>(6, 14)(rng);
        c.layers = std::uniform_int_distribution<int>(1, 3)(rng);
        PoseCheckReport r;
        const std::string refusal = write_and_check(c, dir, written + refused, r);
        if (!refusal.empty()) {
          EXPECT_EQ(refusal.find('\n'), std::string::npos) << c.text() << "\n" << refusal;
          ++refused;
          continue;
        }
        ++written;
        EXPECT_TRUE(r.ok()) << c.text() << "\n" << to_text(r);
      }
    }
  }
  std::printf("mesh jobs: %d written, each checked OK; %d refused with one line\n", written,
              refused);
  EXPECT_GE(written, 9 * kPerPair / 8);
}

// A row moved off its layer's offset surface: the planner's own reading refuses it with the line
// `strand check` prints for it.
TEST(MeshPoseCheckProperty, ThePlannerRefusesWithTheChecksLine) {
  const Case c{"bunny-patch.obj", "kuka-iiwa14-wasp-cylinder", 0, 60.0, 12, 2};
  const std::string dir = testing::fresh_dir("mesh-row-refusal");
  PoseCheckReport r;
  ASSERT_EQ(write_and_check(c, dir, 0, r), "");
  ASSERT_TRUE(r.ok()) << to_text(r);
  const std::string mesh = dir + "/p0.obj";
  const slicer::MeshSubstrate s(slicer::read_mesh_file(mesh), mesh);
  const machines::MachineProfile m = machines::load_profile(c.arm);
  slicer::SubstrateSpec spec;
  spec.type = "mesh";
  spec.mesh_path = mesh;
  const patterns::GeneratorSpec* g = patterns::find_generator("scaffold");
  const slicer::Toolpath t = g->generate(slicer::resolve_params(
      g->table(), {{"nozzle", 0.8}, {"gap", 1.5}, {"size", "12x12"}, {"layers", 2}}));
  MeshJob job = plan_mesh_job(t, spec, m, slicer::kDefaultArcToleranceMm, dir + "/p0.csv");
  auto& pts = job.plan.program.points;
  std::size_t i = pts.size() / 2;
  while (!(pts[i].extrude && pts[i - 1].extrude)) ++i;
  pts[i].contact_mm += 0.2 * pts[i].normal;
  const PoseCheckReport tampered =
      check_mesh_pose_csv(machines::write_pose_csv(job.plan.program), dir + "/p0.csv", m,
                          *find_csv_mesh(dir + "/p0.csv", ""));
  ASSERT_FALSE(tampered.off_surface.listed.empty()) << to_text(tampered);
  EXPECT_EQ(tampered.off_surface.listed.front().row, i);
  try {
    judge_mesh_plan(s, job.plan);
    ADD_FAILURE() << "not refused";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("strand check would reject row " + std::to_string(i)), std::string::npos)
        << what;
    EXPECT_NE(what.find(tampered.off_surface.listed.front().what), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos);
  }
}

}  // namespace
}  // namespace strand::post
