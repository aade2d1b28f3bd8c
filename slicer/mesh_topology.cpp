// Checks of a mesh's indices alone: welding, edge use, fans round vertices (slicer/mesh_topology.h).
#include "slicer/mesh_topology.h"

#include <algorithm>
#include <array>
#include <limits>

namespace strand::slicer {

// Sorted rather than mapped: a tree node per vertex cost more time and memory than the
// mesh itself on a million triangles.
Mesh weld_mesh(const Mesh& m) {
  const std::size_t n = m.vertices_mm.size();
  const auto key = [&](std::size_t i) {
    const Vec3& v = m.vertices_mm[i];
    return std::array<double, 3>{v.x(), v.y(), v.z()};
  };
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const auto ka = key(a), kb = key(b);
    return ka != kb ? ka < kb : a < b;
  });
  std::vector<std::size_t> first(n);  // per vertex, the first vertex at its place
  for (std::size_t k = 0; k < n; ++k) {
    const bool same = k > 0 && !(key(order[k - 1]) < key(order[k]));
    first[order[k]] = same ? first[order[k - 1]] : order[k];
  }
  std::vector<int> remap(n);
  Mesh out;
  for (std::size_t i = 0; i < n; ++i) {
    if (first[i] == i) {  // fresh, in the order of the file
      remap[i] = static_cast<int>(out.vertices_mm.size());
      out.vertices_mm.push_back(m.vertices_mm[i]);
      if (!m.uv.empty()) out.uv.push_back(m.uv[i]);
    } else {
      remap[i] = remap[first[i]];
    }
  }
  for (const auto& t : m.triangles) {
    const std::array<int, 3> r{remap[t[0]], remap[t[1]], remap[t[2]]};
    if (r[0] != r[1] && r[1] != r[2] && r[0] != r[2]) out.triangles.push_back(r);
  }
  return out;
}

namespace {

std::string edge_text(const Mesh& m, int a, int b) {
  return "from " + point_text(m.vertices_mm[a]) + " to " + point_text(m.vertices_mm[b]);
}

}  // namespace

// Border, non-manifold and misoriented edges from directed-edge counts: each use of an edge as
// (lower vertex, higher vertex, 0 when run upwards), sorted, so an edge's uses lie together.
void check_edges(const Mesh& m, MeshCheck& c) {
  std::vector<std::array<int, 3>> uses;
  uses.reserve(3 * m.triangles.size());
  for (const auto& t : m.triangles) {
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      uses.push_back({std::min(a, b), std::max(a, b), a < b ? 0 : 1});
    }
  }
  std::sort(uses.begin(), uses.end());
  std::string border, non_manifold, misoriented;
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i;
    int up = 0, down = 0;
    for (; j < uses.size() && uses[j][0] == uses[i][0] && uses[j][1] == uses[i][1]; ++j) {
      (uses[j][2] == 0 ? up : down) += 1;
    }
    const int a = uses[i][0], b = uses[i][1];
    i = j;
    const int total = up + down;
    if (total == 1) {
      if (c.border_edges++ == 0) border = edge_text(m, a, b);
    } else if (total > 2) {
      if (c.non_manifold_edges++ == 0) non_manifold = edge_text(m, a, b);
    } else if (up != 1) {
      if (c.misoriented_edges++ == 0) misoriented = edge_text(m, a, b);
    }
  }
  if (c.border_edges > 0) {
    c.problem = "open mesh: " + std::to_string(c.border_edges) + " border edge(s), e.g. " + border;
  } else if (c.non_manifold_edges > 0) {
    c.problem = "non-manifold: " + std::to_string(c.non_manifold_edges) +
                " edge(s) shared by 3 or more triangles, e.g. " + non_manifold;
  } else if (c.misoriented_edges > 0) {
    c.problem = "inconsistently oriented: " + std::to_string(c.misoriented_edges) +
                " edge(s) run the same way by both triangles, e.g. " + misoriented;
  }
}

// Whether the triangles around some vertex form more than one fan: surfaces that touch at a
// single vertex. The edges are sound (each used once each way), so the edges opposite a vertex,
// each run from the triangle's next corner to its last, make a permutation of its neighbours:
// one cycle around a sound vertex, several at a touching one. (CGAL's
// is_polygon_soup_a_polygon_mesh answers the same for any soup, at ten times the cost here.)
bool touches_at_a_vertex(const Mesh& m) {
  std::vector<std::size_t> first(m.vertices_mm.size() + 1, 0);
  for (const auto& t : m.triangles) {
    for (const int v : t) ++first[static_cast<std::size_t>(v) + 1];
  }
  for (std::size_t v = 1; v < first.size(); ++v) first[v] += first[v - 1];
  std::vector<std::pair<int, int>> opposite(first.back());  // per vertex, its link's edges
  std::vector<std::size_t> next = first;
  for (const auto& t : m.triangles) {
    for (int k = 0; k < 3; ++k) opposite[next[t[k]]++] = {t[(k + 1) % 3], t[(k + 2) % 3]};
  }
  for (std::size_t v = 0; v + 1 < first.size(); ++v) {
    const auto begin = opposite.begin() + static_cast<std::ptrdiff_t>(first[v]);
    const auto end = opposite.begin() + static_cast<std::ptrdiff_t>(first[v + 1]);
    if (begin == end) continue;
    std::sort(begin, end);
    const int start = begin->first;
    int at = start;
    std::ptrdiff_t steps = 0;
    do {
      const auto e = std::lower_bound(begin, end, std::make_pair(at, std::numeric_limits<int>::min()));
      if (e == end || e->first != at) return true;  // not a permutation: edges not sound
      at = e->second;
      ++steps;
    } while (at != start && steps <= end - begin);
    if (steps != end - begin) return true;
  }
  return false;
}

}  // namespace strand::slicer
