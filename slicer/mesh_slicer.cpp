// CGAL Polygon_mesh_slicer on a Surface_mesh with an AABB tree of its edges.
#include "slicer/mesh_slicer.h"

#include <CGAL/AABB_halfedge_graph_segment_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_slicer.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <list>

#include "slicer/tolerances.h"

namespace strand::slicer {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;
using Primitive = CGAL::AABB_halfedge_graph_segment_primitive<SurfaceMesh>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;
using Slicer = CGAL::Polygon_mesh_slicer<SurfaceMesh, K>;

}  // namespace

struct MeshSlicer::Impl {
  SurfaceMesh mesh;
  Tree tree;
  std::unique_ptr<Slicer> slicer;
  std::vector<double> vertex_z;  // sorted, to move planes off vertices
};

MeshSlicer::MeshSlicer(const Mesh& m) : impl_(std::make_unique<Impl>()) {
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  for (const Vec3& v : m.vertices_mm) points.emplace_back(v.x(), v.y(), v.z());
  for (const auto& t : m.triangles) {
    polygons.push_back({static_cast<std::size_t>(t[0]), static_cast<std::size_t>(t[1]),
                        static_cast<std::size_t>(t[2])});
  }
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, polygons, impl_->mesh);
  impl_->tree.insert(edges(impl_->mesh).first, edges(impl_->mesh).second, impl_->mesh);
  impl_->tree.build();
  impl_->slicer = std::make_unique<Slicer>(impl_->mesh, impl_->tree);
  for (const Vec3& v : m.vertices_mm) impl_->vertex_z.push_back(v.z());
  std::sort(impl_->vertex_z.begin(), impl_->vertex_z.end());
}

MeshSlicer::~MeshSlicer() = default;

std::vector<Ring> slice_at(const MeshSlicer& s, double z_mm) {
  const auto& impl = s.impl();
  double z = z_mm;
  while (std::binary_search(impl.vertex_z.begin(), impl.vertex_z.end(), z)) z += kSliceNudgeMm;
  std::list<std::vector<Point>> polylines;
  (*impl.slicer)(K::Plane_3(0, 0, 1, -z), std::back_inserter(polylines));
  std::vector<Ring> out;
  for (const auto& pl : polylines) {
    if (pl.size() < 4 || pl.front() != pl.back()) continue;  // open, or fewer than 3 corners
    Ring c;
    c.reserve(pl.size() - 1);
    for (std::size_t i = 0; i + 1 < pl.size(); ++i) c.emplace_back(pl[i].x(), pl[i].y());
    out.push_back(std::move(c));
  }
  return out;
}

std::vector<Region> slice_layers(const Mesh& m, double layer_height_mm, int layers) {
  const MeshSlicer slicer(m);
  std::vector<Region> out;
  out.reserve(static_cast<std::size_t>(layers));
  for (int k = 0; k < layers; ++k) {
    out.push_back(region_from_contours(slice_at(slicer, (k + 0.5) * layer_height_mm)));
  }
  return out;
}

}  // namespace strand::slicer
