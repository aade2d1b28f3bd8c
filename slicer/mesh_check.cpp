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

#include <cmath>
#include <map>

#include "slicer/input_error.h"

namespace strand::slicer {

namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;
using Soup = std::vector<std::vector<std::size_t>>;

}  // namespace

Mesh weld_mesh(const Mesh& m) {
  std::map<std::array<double, 3>, int> index;
  std::vector<int> remap(m.vertices_mm.size());
  Mesh out;
  for (std::size_t i = 0; i < m.vertices_mm.size(); ++i) {
    const Vec3& v = m.vertices_mm[i];
    const auto [it, fresh] = index.emplace(std::array<double, 3>{v.x(), v.y(), v.z()},
                                           static_cast<int>(out.vertices_mm.size()));
    if (fresh) {
      out.vertices_mm.push_back(v);
      if (!m.uv.empty()) out.uv.push_back(m.uv[i]);
    }
    remap[i] = it->second;
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

// Border, non-manifold and misoriented edges from directed-edge counts.
void check_edges(const Mesh& m, MeshCheck& c) {
  std::map<std::pair<int, int>, std::pair<int, int>> uses;  // undirected -> (a->b, b->a)
  for (const auto& t : m.triangles) {
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      auto& u = uses[{std::min(a, b), std::max(a, b)}];
      (a < b ? u.first : u.second) += 1;
    }
  }
  std::string border, non_manifold, misoriented;
  for (const auto& [e, u] : uses) {
    const int total = u.first + u.second;
    if (total == 1) {
      if (c.border_edges++ == 0) border = edge_text(m, e.first, e.second);
    } else if (total > 2) {
      if (c.non_manifold_edges++ == 0) non_manifold = edge_text(m, e.first, e.second);
    } else if (u.first != 1) {
      if (c.misoriented_edges++ == 0) misoriented = edge_text(m, e.first, e.second);
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
void check_geometry(const Mesh& m, MeshCheck& c) {
  std::vector<Point> points;
  Soup polygons;
  to_soup(m, points, polygons);
  if (!PMP::is_polygon_soup_a_polygon_mesh(polygons)) {
    c.problem = "non-manifold: surfaces touch at a single vertex";
    return;
  }
  SurfaceMesh sm;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, sm);
  if (PMP::does_self_intersect(sm)) {
    std::vector<std::pair<SurfaceMesh::Face_index, SurfaceMesh::Face_index>> pairs;
    PMP::self_intersections(sm, std::back_inserter(pairs));
    c.self_intersections = pairs.size();
    const auto h = sm.halfedge(pairs.front().first);
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

MeshCheck check_mesh(const Mesh& input) {
  const Mesh m = weld_mesh(input);
  MeshCheck c;
  check_edges(m, c);
  if (c.ok()) check_geometry(m, c);
  return c;
}

PreparedMesh prepare_mesh(const Mesh& input, bool repair, const std::string& what) {
  PreparedMesh out;
  out.mesh = weld_mesh(input);
  const Vec3 size = bounds(out.mesh).size_mm();
  if (size.minCoeff() <= 0.0) {
    throw InputError(what + ": flat mesh (size " + point_text(size) + " mm): nothing to fill");
  }
  const std::size_t merged = input.vertices_mm.size() - out.mesh.vertices_mm.size();
  out.before = check_mesh(out.mesh);
  if (!out.before.ok()) {
    if (!repair)
      throw InputError(what + ": " + out.before.problem + " (run with --repair to fix it)");
    if (merged > 0) out.changes.push_back("merged coincident vertices: " + std::to_string(merged));
    out.mesh = weld_mesh(repaired(out.mesh, out.changes));
    const MeshCheck after = check_mesh(out.mesh);
    if (!after.ok()) {
      const bool cut = after.self_intersections > 0;
      throw InputError(what + ": " + after.problem +
                       (cut ? " (--repair does not cut self-intersections: export the part as one "
                              "closed surface)"
                            : " (still after --repair)"));
    }
    if (after.inside_out) out.before.inside_out = true;
  }
  if (out.before.inside_out) {
    for (auto& t : out.mesh.triangles) std::swap(t[1], t[2]);
    out.changes.push_back("reversed inward-facing triangles");
  }
  if (!(std::abs(signed_volume_mm3(out.mesh)) > 1e-9 * size.prod())) {
    throw InputError(what + ": zero volume (degenerate triangles only)");
  }
  return out;
}

}  // namespace strand::slicer
