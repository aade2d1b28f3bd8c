// Vertex clustering (slicer/mesh_decimate.h).
#include "slicer/mesh_decimate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <unordered_map>
#include <unordered_set>

namespace strand::slicer {

namespace {

struct Key {
  std::int64_t x, y, z;
  bool operator==(const Key&) const = default;
};

struct KeyHash {
  std::size_t operator()(const Key& k) const {
    const auto u = [](std::int64_t v) { return static_cast<std::uint64_t>(v); };
    return std::hash<std::uint64_t>()(u(k.x) * 73856093u ^ u(k.y) * 19349663u ^ u(k.z) * 83492791u);
  }
};

struct TriHash {
  std::size_t operator()(const std::array<int, 3>& t) const {
    const auto u = [](int v) { return static_cast<std::uint64_t>(static_cast<std::uint32_t>(v)); };
    return std::hash<std::uint64_t>()((u(t[0]) * 1000003u + u(t[1])) * 1000003u + u(t[2]));
  }
};

// One pass at cell size `cell`: vertices to their cells' means, triangles re-indexed, the ones
// whose corners met or that repeat another (either winding) dropped.
Mesh cluster(const Mesh& m, const Vec3& origin, double cell) {
  std::unordered_map<Key, int, KeyHash> cell_of;
  std::vector<int> index(m.vertices_mm.size());
  std::vector<Vec3> sum;
  std::vector<int> count;
  for (std::size_t i = 0; i < m.vertices_mm.size(); ++i) {
    const Vec3 q = (m.vertices_mm[i] - origin) / cell;
    const Key k{static_cast<std::int64_t>(std::floor(q.x())), static_cast<std::int64_t>(std::floor(q.y())),
                static_cast<std::int64_t>(std::floor(q.z()))};
    const auto [it, fresh] = cell_of.emplace(k, static_cast<int>(sum.size()));
    if (fresh) sum.push_back(Vec3::Zero()), count.push_back(0);
    index[i] = it->second;
    sum[static_cast<std::size_t>(it->second)] += m.vertices_mm[i];
    ++count[static_cast<std::size_t>(it->second)];
  }
  Mesh out;
  out.vertices_mm.reserve(sum.size());
  for (std::size_t c = 0; c < sum.size(); ++c) out.vertices_mm.push_back(sum[c] / count[c]);
  std::unordered_set<std::array<int, 3>, TriHash> seen;
  for (const auto& t : m.triangles) {
    const std::array<int, 3> r{index[static_cast<std::size_t>(t[0])], index[static_cast<std::size_t>(t[1])],
                               index[static_cast<std::size_t>(t[2])]};
    if (r[0] == r[1] || r[1] == r[2] || r[0] == r[2]) continue;
    std::array<int, 3> key = r;
    std::sort(key.begin(), key.end());
    if (!seen.insert(key).second) continue;
    out.triangles.push_back(r);
  }
  return out;
}

}  // namespace

Decimated decimate_for_drawing(const Mesh& m, std::size_t max_triangles) {
  Decimated d;
  if (m.triangles.size() <= max_triangles || m.vertices_mm.empty()) {
    d.mesh = m;
    d.mesh.uv.clear();
    return d;
  }
  const Box3 box = bounds(m);
  const double diagonal = std::max(box.size_mm().norm(), 1e-9);
  // About two triangles per cell the surface passes through: area / cell^2 cells.
  const double n = static_cast<double>(std::max<std::size_t>(max_triangles, 1));
  const double area = surface_area_mm2(m);
  double cell = area > 0 ? std::sqrt(2.0 * area / n) : diagonal / std::sqrt(n);
  // A cell as big as the box leaves no triangle, so this ends.
  for (;;) {
    d.mesh = cluster(m, box.min_mm, cell);
    d.cell_mm = cell;
    if (d.mesh.triangles.size() <= max_triangles || cell > 2 * diagonal) break;
    cell *= 1.25;
  }
  return d;
}

}  // namespace strand::slicer
