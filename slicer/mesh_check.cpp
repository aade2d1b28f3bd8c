// Topology checks on the index soup (where, with coordinates), CGAL PMP for
// self-intersections, orientation, stitching and hole filling.
#include "slicer/mesh_check.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_mesh_to_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/stitch_borders.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "slicer/input_error.h"
#include "slicer/mesh_topology.h"

namespace strand::slicer {

namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;
using Soup = std::vector<std::vector<std::size_t>>;

void to_soup(const Mesh& m, std::vector<Point>& points, Soup& polygons) {
  points.clear();
  polygons.clear();
  for (const Vec3& v : m.vertices_mm) points.emplace_back(v.x(), v.y(), v.z());
  for (const auto& t : m.triangles) {
    polygons.push_back({static_cast<std::size_t>(t[0]), static_cast<std::size_t>(t[1]),
                        static_cast<std::size_t>(t[2])});
  }
}

Mesh from_surface_mesh(const SurfaceMesh& sm) {
  std::vector<Point> points;
  Soup polygons;
  PMP::polygon_mesh_to_polygon_soup(sm, points, polygons);
  Mesh m;
  for (const Point& p : points) m.vertices_mm.emplace_back(p.x(), p.y(), p.z());
  for (const auto& f : polygons) {
    for (std::size_t k = 1; k + 1 < f.size(); ++k) {  // fans, should a hole patch be a polygon
      m.triangles.push_back(
          {static_cast<int>(f[0]), static_cast<int>(f[k]), static_cast<int>(f[k + 1])});
    }
  }
  return m;
}

// Self-intersections and orientation of a mesh whose edges are sound.
void check_geometry(const Mesh& m, MeshCheck& c, Crossings crossings) {
  std::vector<Point> points;
  Soup polygons;
  to_soup(m, points, polygons);
  if (touches_at_a_vertex(m)) {
    c.touching_vertex = true;
    c.problem = "non-manifold: surfaces touch at a single vertex";
    return;
  }
  SurfaceMesh sm;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, sm);
  // On every core (oneTBB). Up to the first pair: it stops there. Counted: the pairs come in
  // any order, so the example named is the least face.
  if (crossings == Crossings::First &&
      PMP::does_self_intersect<CGAL::Parallel_if_available_tag>(sm)) {
    c.self_intersecting = true;
    c.problem = "self-intersecting: triangles cut each other";
    return;
  }
  std::vector<std::pair<SurfaceMesh::Face_index, SurfaceMesh::Face_index>> pairs;
  if (crossings == Crossings::Count) {
    PMP::self_intersections<CGAL::Parallel_if_available_tag>(sm, std::back_inserter(pairs));
  }
  if (!pairs.empty()) {
    c.self_intersections = pairs.size();
    c.self_intersecting = true;
    SurfaceMesh::Face_index least = pairs.front().first;
    for (const auto& [f, g] : pairs) least = std::min({least, f, g});
    const auto h = sm.halfedge(least);
    const Point p = CGAL::centroid(sm.point(sm.source(h)), sm.point(sm.target(h)),
                                   sm.point(sm.target(sm.next(h))));
    c.problem = "self-intersecting: " + std::to_string(pairs.size()) +
                " pair(s) of triangles cut each other, e.g. near " +
                point_text(Vec3(p.x(), p.y(), p.z()));
    return;
  }
  c.inside_out = !PMP::is_outward_oriented(sm);
}

void add_change(std::vector<std::string>& changes, std::size_t n, const std::string& what) {
  if (n > 0) changes.push_back(what + " " + std::to_string(n));
}

// Soup repair, orientation, stitching and hole filling; returns the repaired mesh.
Mesh repaired(const Mesh& m, std::vector<std::string>& changes) {
  std::vector<Point> points;
  Soup polygons;
  to_soup(m, points, polygons);
  const std::size_t before = polygons.size();
  PMP::repair_polygon_soup(points, polygons);
  add_change(changes, before - polygons.size(), "removed degenerate or duplicate triangles:");
  if (!PMP::orient_polygon_soup(points, polygons)) {
    changes.push_back("re-oriented triangles; split non-manifold vertices or edges");
  }
  SurfaceMesh sm;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, sm);
  add_change(changes, PMP::stitch_borders(sm), "stitched border edge pairs:");
  std::vector<SurfaceMesh::Halfedge_index> cycles;
  PMP::extract_boundary_cycles(sm, std::back_inserter(cycles));
  std::size_t filled = 0, added = 0;
  for (const auto h : cycles) {
    std::size_t edges = 0;
    for (auto e : CGAL::halfedges_around_face(h, sm)) {
      (void)e;
      ++edges;
    }
    if (edges > kMaxRepairHoleEdges) continue;
    std::vector<SurfaceMesh::Face_index> patch;
    PMP::triangulate_hole(sm, h, std::back_inserter(patch));
    filled += patch.empty() ? 0 : 1;
    added += patch.size();
  }
  if (filled > 0) {
    changes.push_back("filled holes: " + std::to_string(filled) + " (" + std::to_string(added) +
                      " triangles)");
  }
  return from_surface_mesh(sm);
}

}  // namespace

namespace {

// check_mesh of a mesh welded already (weld_mesh changes nothing the second time).
MeshCheck check_welded(const Mesh& m, Crossings crossings) {
  MeshCheck c;
  check_edges(m, c);
  if (c.ok()) check_geometry(m, c, crossings);
  return c;
}

}  // namespace

MeshCheck check_mesh(const Mesh& input, Crossings crossings) {
  return check_welded(weld_mesh(input), crossings);
}

MeshCheck check_edges_as_indexed(const Mesh& m) {
  MeshCheck c;
  check_edges(m, c);
  return c;
}

namespace {

// Triangles on the same three vertices: copies run the same way are one triangle, a pair run
// opposite ways is a sheet of no volume (or two shells glued face to face) and goes.
std::size_t drop_doubled_triangles(Mesh& m) {
  std::map<std::array<int, 3>, std::vector<std::size_t>> by_corners;
  for (std::size_t i = 0; i < m.triangles.size(); ++i) {
    std::array<int, 3> k = m.triangles[i];
    std::sort(k.begin(), k.end());
    by_corners[k].push_back(i);
  }
  std::vector<char> keep(m.triangles.size(), 1);
  std::size_t dropped = 0;
  for (const auto& [corners, ids] : by_corners) {
    if (ids.size() < 2) continue;
    // +1 for each copy that is an even permutation of the sorted corners, -1 otherwise.
    int net = 0;
    for (const std::size_t i : ids) {
      const auto& t = m.triangles[i];
      const bool even = (t[0] == corners[0] && t[1] == corners[1]) ||
                        (t[1] == corners[0] && t[2] == corners[1]) ||
                        (t[2] == corners[0] && t[0] == corners[1]);
      net += even ? 1 : -1;
    }
    bool kept = false;
    for (const std::size_t i : ids) {
      const auto& t = m.triangles[i];
      const bool even = (t[0] == corners[0] && t[1] == corners[1]) ||
                        (t[1] == corners[0] && t[2] == corners[1]) ||
                        (t[2] == corners[0] && t[0] == corners[1]);
      if (!kept && net != 0 && even == (net > 0)) {
        kept = true;
        continue;
      }
      keep[i] = 0;
      ++dropped;
    }
  }
  if (dropped > 0) {
    std::vector<std::array<int, 3>> kept_triangles;
    for (std::size_t i = 0; i < m.triangles.size(); ++i) {
      if (keep[i]) kept_triangles.push_back(m.triangles[i]);
    }
    m.triangles = std::move(kept_triangles);
  }
  return dropped;
}

std::string count_text(std::size_t n, const std::string& one, const std::string& many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

// What the soup slicer does with each defect, for the summary and the report.
std::vector<std::string> defect_notes(const MeshCheck& c) {
  std::vector<std::string> out;
  if (c.self_intersections > 0) {
    out.push_back(
        "mesh: " +
        count_text(c.self_intersections, "self-intersecting pair", "self-intersecting pairs") +
        " of triangles resolved by contour union");
  } else if (c.self_intersecting) {
    out.push_back(
        "mesh: self-intersecting triangles resolved by contour union (strand mesh "
        "counts the pairs)");
  }
  if (c.non_manifold_edges > 0) {
    out.push_back("mesh: " + count_text(c.non_manifold_edges, "edge", "edges") +
                  " shared by 3 or more triangles (non-manifold) sliced as a triangle soup");
  }
  if (c.touching_vertex) {
    out.push_back(
        "mesh: surfaces touching at a single vertex (non-manifold) sliced as a triangle soup");
  }
  if (c.border_edges > 0) {
    out.push_back("mesh: open surface (" +
                  count_text(c.border_edges, "border edge", "border edges") +
                  "); contours closed across the gaps");
  }
  if (c.misoriented_edges > 0) {
    out.push_back("mesh: " + count_text(c.misoriented_edges, "edge", "edges") +
                  " between triangles facing opposite ways; contours follow them either way");
  }
  return out;
}

}  // namespace

namespace {

struct UnionFind {
  std::vector<std::size_t> parent;
  explicit UnionFind(std::size_t n) : parent(n) {
    for (std::size_t i = 0; i < n; ++i) parent[i] = i;
  }
  std::size_t find(std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void join(std::size_t a, std::size_t b) { parent[find(a)] = find(b); }
};

}  // namespace

MeshInfo mesh_info(const Mesh& input) {
  MeshInfo info;
  info.triangles = input.triangles.size();
  info.vertices = input.vertices_mm.size();
  info.size = bounds(input).size_mm();
  const Mesh m = weld_mesh(input);
  info.volume = signed_volume_mm3(m);
  info.check = check_mesh(m);
  info.crossings_searched = info.check.border_edges == 0 && info.check.non_manifold_edges == 0 &&
                            info.check.misoriented_edges == 0 && !info.check.touching_vertex;
  const std::size_t nv = m.vertices_mm.size(), nt = m.triangles.size();
  UnionFind shells(nv), borders(nv), corners(3 * nt);
  std::map<std::pair<int, int>, std::vector<std::size_t>> edge_triangles;
  for (std::size_t t = 0; t < nt; ++t) {
    const auto& tri = m.triangles[t];
    for (int k = 0; k < 3; ++k) {
      const int a = tri[static_cast<std::size_t>(k)],
                b = tri[static_cast<std::size_t>((k + 1) % 3)];
      shells.join(static_cast<std::size_t>(a), static_cast<std::size_t>(b));
      edge_triangles[{std::min(a, b), std::max(a, b)}].push_back(t);
    }
  }
  auto corner = [&](std::size_t t, int v) {
    for (std::size_t k = 0; k < 3; ++k) {
      if (m.triangles[t][k] == v) return 3 * t + k;
    }
    return 3 * t;
  };
  std::vector<char> on_border(nv, 0);
  for (const auto& [e, ts] : edge_triangles) {
    if (ts.size() == 1) {
      borders.join(static_cast<std::size_t>(e.first), static_cast<std::size_t>(e.second));
      on_border[static_cast<std::size_t>(e.first)] = on_border[static_cast<std::size_t>(e.second)] =
          1;
    }
    if (ts.size() != 2) continue;  // fans join through manifold edges only
    for (const int v : {e.first, e.second}) corners.join(corner(ts[0], v), corner(ts[1], v));
  }
  std::vector<char> used(nv, 0);
  for (const auto& t : m.triangles) {
    for (const int v : t) used[static_cast<std::size_t>(v)] = 1;
  }
  std::map<std::size_t, char> shell_roots, border_roots;
  for (std::size_t v = 0; v < nv; ++v) {
    if (used[v]) shell_roots[shells.find(v)] = 1;
    if (on_border[v]) border_roots[borders.find(v)] = 1;
  }
  info.shells = shell_roots.size();
  info.holes = border_roots.size();
  std::vector<std::vector<std::size_t>> fans(nv);
  for (std::size_t t = 0; t < nt; ++t) {
    for (std::size_t k = 0; k < 3; ++k) {
      fans[static_cast<std::size_t>(m.triangles[t][k])].push_back(corners.find(3 * t + k));
    }
  }
  for (auto& f : fans) {
    std::sort(f.begin(), f.end());
    if (std::unique(f.begin(), f.end()) - f.begin() > 1) ++info.non_manifold_vertices;
  }
  return info;
}

PreparedMesh prepare_mesh(const Mesh& input, bool repair, const std::string& what) {
  return prepare_mesh(input, PrepareOptions{repair, true}, what);
}

PreparedMesh prepare_mesh(const Mesh& input, const PrepareOptions& options,
                          const std::string& what) {
  PreparedMesh out;
  out.mesh = weld_mesh(input);
  const Vec3 size = bounds(out.mesh).size_mm();
  if (size.minCoeff() <= 0.0) {
    throw InputError(what + ": flat mesh (size " + point_text(size) + " mm): nothing to fill");
  }
  const std::size_t merged = input.vertices_mm.size() - out.mesh.vertices_mm.size();
  // Slicing needs to know whether triangles cross, not how many pairs do; a refusal counts
  // them and names where.
  const auto counted = [](const Mesh& m, const MeshCheck& c) {
    return c.self_intersecting && c.self_intersections == 0 ? check_mesh(m) : c;
  };
  out.before = check_welded(out.mesh, Crossings::First);
  MeshCheck sliced = out.before;
  if (!out.before.ok()) {
    if (options.strict && !options.repair) {
      throw InputError(what + ": " + counted(out.mesh, out.before).problem +
                       " (run with --repair to fix it)");
    }
    if (options.repair) {
      std::vector<std::string> changes;
      if (merged > 0) changes.push_back("merged coincident vertices: " + std::to_string(merged));
      Mesh fixed = repaired(out.mesh, changes);
      // Never worse than the file: the mesh as indexed there against the repaired one.
      const MeshCheck was = check_edges_as_indexed(input), now = check_edges_as_indexed(fixed);
      if (now.non_manifold_edges > was.non_manifold_edges || now.border_edges > was.border_edges ||
          now.misoriented_edges > was.misoriented_edges) {
        out.changes.push_back(
            "repair left out: it would add border, non-manifold or misoriented edges");
      } else {
        out.changes.insert(out.changes.end(), changes.begin(), changes.end());
        out.mesh = std::move(fixed);
      }
      sliced = check_mesh(out.mesh, Crossings::First);
      if (options.strict && !sliced.ok()) {
        const bool cut = sliced.self_intersecting;
        throw InputError(what + ": " + counted(out.mesh, sliced).problem +
                         (cut ? " (--repair does not cut self-intersections: export the part as "
                                "one closed surface)"
                              : " (still after --repair)"));
      }
      if (sliced.ok()) out.before.inside_out = out.before.inside_out || sliced.inside_out;
    }
  }
  if (!sliced.ok()) {
    out.defects = defect_notes(sliced);
    const std::size_t doubled = drop_doubled_triangles(out.mesh);
    if (doubled > 0) {
      out.defects.push_back(
          "mesh: " + count_text(doubled, "doubled triangle", "doubled triangles") +
          " left out (copies, or pairs facing opposite ways)");
    }
    if (signed_volume_mm3(out.mesh) < 0.0) out.before.inside_out = true;
  }
  if (out.before.inside_out) {
    for (auto& t : out.mesh.triangles) std::swap(t[1], t[2]);
    out.changes.push_back("reversed inward-facing triangles");
  }
  if (!(std::abs(signed_volume_mm3(out.mesh)) > 1e-9 * size.prod())) {
    throw InputError(what +
                     ": no volume (every triangle degenerate, or every shell open and flat)");
  }
  return out;
}

}  // namespace strand::slicer
