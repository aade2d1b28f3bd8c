// Mesh patches as surfaces: UVs (file or CGAL LSCM) scaled to mm, a grid to find the
// triangle holding (u, v), barycentric points, smoothed normals and the map's Jacobian.
#include "slicer/mesh_surface.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/LSCM_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Two_vertices_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "slicer/input_error.h"
#include "slicer/mesh_check.h"

namespace strand::slicer {

namespace {

namespace SMP = CGAL::Surface_mesh_parameterization;
namespace PMP = CGAL::Polygon_mesh_processing;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<K::Point_3>;

// Least-squares conformal map of a disk-like patch (CGAL), one UV per vertex.
std::vector<Vec2> lscm_uv(const Mesh& m, const std::string& source) {
  std::vector<K::Point_3> points;
  std::vector<std::vector<std::size_t>> polygons;
  for (const Vec3& v : m.vertices_mm) points.emplace_back(v.x(), v.y(), v.z());
  for (const auto& t : m.triangles)
    polygons.push_back({std::size_t(t[0]), std::size_t(t[1]), std::size_t(t[2])});
  if (!PMP::is_polygon_soup_a_polygon_mesh(polygons)) {
    throw InputError("onto = " + source +
                     ": not a manifold surface patch (edges shared by 3+ triangles or flipped)");
  }
  SurfaceMesh sm;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, sm);
  std::vector<SurfaceMesh::Halfedge_index> borders;
  PMP::extract_boundary_cycles(sm, std::back_inserter(borders));
  const long euler = static_cast<long>(sm.number_of_vertices()) -
                     static_cast<long>(sm.number_of_edges()) +
                     static_cast<long>(sm.number_of_faces());
  if (borders.size() != 1 || euler != 1) {
    throw InputError("onto = " + source + ": not a disk-like patch (" +
                     std::to_string(borders.size()) + " border(s), Euler characteristic " +
                     std::to_string(euler) + "; need 1 and 1) and no UVs in the file");
  }
  auto uvmap = sm.add_property_map<SurfaceMesh::Vertex_index, K::Point_2>("v:uv").first;
  using Parameterizer =
      SMP::LSCM_parameterizer_3<SurfaceMesh, SMP::Two_vertices_parameterizer_3<SurfaceMesh>>;
  const SMP::Error_code err =
      SMP::parameterize(sm, Parameterizer(), PMP::longest_border(sm).first, uvmap);
  if (err != SMP::OK) {
    throw InputError("onto = " + source + ": parameterisation failed (" +
                     SMP::get_error_message(err) + ")");
  }
  std::vector<Vec2> uv;
  for (const auto v : sm.vertices()) uv.emplace_back(uvmap[v].x(), uvmap[v].y());
  return uv;
}

double uv_double_area(const std::vector<Vec2>& uv, const std::array<int, 3>& t) {
  return cross(uv[t[1]] - uv[t[0]], uv[t[2]] - uv[t[0]]);
}

// Scales UVs so the patch's (u, v) area equals its 3D area, centres them on (0, 0), and,
// for a computed map, turns them to line up with the patch's top view (least squares).
void normalise_uv(const Mesh& m, std::vector<Vec2>& uv, bool align, const std::string& source) {
  double a3 = 0.0, a2 = 0.0;
  int positive = 0;
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    a3 += triangle_double_area_mm2(m, static_cast<int>(t));
    const double a = uv_double_area(uv, m.triangles[t]);
    a2 += a;
    positive += a > 0;
  }
  const int n = static_cast<int>(m.triangles.size());
  if (positive != 0 && positive != n) {
    throw InputError("onto = " + source + ": the UV map folds over (" +
                     std::to_string(std::min(positive, n - positive)) + " of " + std::to_string(n) +
                     " triangles flipped)");
  }
  if (a2 < 0) {
    for (Vec2& q : uv) q.y() = -q.y();  // mirrored map: keep (u, v) counter-clockwise
  }
  const double scale = std::sqrt(a3 / std::abs(a2));
  Vec2 lo = uv.front(), hi = uv.front();
  for (const Vec2& q : uv) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
  const Vec2 c = (lo + hi) / 2.0;
  for (Vec2& q : uv) q = (q - c) * scale;
  if (!align) return;
  Vec2 cx = Vec2::Zero();
  for (const Vec3& v : m.vertices_mm) cx += v.head<2>();
  cx /= static_cast<double>(m.vertices_mm.size());
  double sc = 0.0, ss = 0.0;  // best rotation of uv onto the top view: atan2(sum cross, sum dot)
  for (std::size_t i = 0; i < uv.size(); ++i) {
    const Vec2 p = m.vertices_mm[i].head<2>() - cx;
    sc += uv[i].dot(p);
    ss += cross(uv[i], p);
  }
  const double a = std::atan2(ss, sc);
  const Eigen::Rotation2Dd r(a);
  for (Vec2& q : uv) q = r * q;
}

}  // namespace

struct MeshSurface::Impl {
  Mesh mesh;
  std::vector<Vec2> uv;      // mm, per vertex
  std::vector<Vec3> normal;  // unit, per vertex, towards the nozzle
  std::string source, uv_source;
  MapDistortion distortion;
  UvBox box;
  double cell = 1.0;
  int nx = 1, ny = 1;
  std::vector<std::vector<int>> grid;  // triangles overlapping each (u, v) cell
  double top_z = 0.0;

  void build_grid();
  void build_normals();
  void measure();
  // Triangle holding uv and its barycentric weights; -1 when none (outside).
  int locate(const Vec2& uv, Vec3& bary) const;
};

void MeshSurface::Impl::build_grid() {
  box = {uv.front(), uv.front()};
  for (const Vec2& q : uv) box.min_mm = box.min_mm.cwiseMin(q), box.max_mm = box.max_mm.cwiseMax(q);
  const Vec2 size = (box.max_mm - box.min_mm).cwiseMax(Vec2(1e-6, 1e-6));
  cell = std::max(std::sqrt(size.prod() / std::max<double>(1.0, mesh.triangles.size())) * 2.0,
                  size.maxCoeff() / 1024);
  nx = static_cast<int>(size.x() / cell) + 1;
  ny = static_cast<int>(size.y() / cell) + 1;
  grid.assign(static_cast<std::size_t>(nx) * ny, {});
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& f = mesh.triangles[t];
    const Vec2 lo = uv[f[0]].cwiseMin(uv[f[1]]).cwiseMin(uv[f[2]]) - box.min_mm;
    const Vec2 hi = uv[f[0]].cwiseMax(uv[f[1]]).cwiseMax(uv[f[2]]) - box.min_mm;
    for (int y = std::max(0, int(lo.y() / cell)); y <= std::min(ny - 1, int(hi.y() / cell)); ++y) {
      for (int x = std::max(0, int(lo.x() / cell)); x <= std::min(nx - 1, int(hi.x() / cell));
           ++x) {
        grid[static_cast<std::size_t>(y) * nx + x].push_back(static_cast<int>(t));
      }
    }
  }
}

void MeshSurface::Impl::build_normals() {
  normal.assign(mesh.vertices_mm.size(), Vec3::Zero());
  Vec3 sum = Vec3::Zero();
  for (const auto& f : mesh.triangles) {
    const Vec3 n = (mesh.vertices_mm[f[1]] - mesh.vertices_mm[f[0]])
                       .cross(mesh.vertices_mm[f[2]] - mesh.vertices_mm[f[0]]);
    for (int k = 0; k < 3; ++k) normal[f[k]] += n;  // area-weighted
    sum += n;
  }
  const double sign = sum.z() < 0 ? -1.0 : 1.0;  // the side facing up faces the nozzle
  for (Vec3& n : normal) n = n.norm() > 0 ? Vec3(sign * n.normalized()) : Vec3::UnitZ();
  top_z = mesh.vertices_mm.front().z();
  for (const Vec3& v : mesh.vertices_mm) top_z = std::max(top_z, v.z());
}

void MeshSurface::Impl::measure() {
  bool first = true;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& f = mesh.triangles[t];
    const double a2 = std::abs(uv_double_area(uv, f));
    if (a2 <= 0) continue;
    const double ratio = triangle_double_area_mm2(mesh, static_cast<int>(t)) / a2;
    Eigen::Matrix<double, 3, 2> e;
    e << mesh.vertices_mm[f[1]] - mesh.vertices_mm[f[0]],
        mesh.vertices_mm[f[2]] - mesh.vertices_mm[f[0]];
    Eigen::Matrix2d g;
    g << uv[f[1]] - uv[f[0]], uv[f[2]] - uv[f[0]];
    const Eigen::Matrix<double, 3, 2> j = e * g.inverse();
    const Eigen::Vector2d sv = Eigen::JacobiSVD<Eigen::Matrix<double, 3, 2>>(j).singularValues();
    const double stretch = sv(1) > 0 ? sv(0) / sv(1) : 1e9;
    distortion.area_ratio_min = first ? ratio : std::min(distortion.area_ratio_min, ratio);
    distortion.area_ratio_max = first ? ratio : std::max(distortion.area_ratio_max, ratio);
    distortion.stretch_max = first ? stretch : std::max(distortion.stretch_max, stretch);
    first = false;
  }
}

int MeshSurface::Impl::locate(const Vec2& q, Vec3& bary) const {
  const Vec2 rel = q - box.min_mm;
  const int x = static_cast<int>(std::floor(rel.x() / cell)),
            y = static_cast<int>(std::floor(rel.y() / cell));
  if (x < 0 || y < 0 || x >= nx || y >= ny) return -1;
  constexpr double kInsideSlack = 1e-9;  // barycentric slack on shared edges
  for (int t : grid[static_cast<std::size_t>(y) * nx + x]) {
    const auto& f = mesh.triangles[static_cast<std::size_t>(t)];
    const double a = uv_double_area(uv, f);
    const double b0 = cross(uv[f[1]] - q, uv[f[2]] - q) / a;
    const double b1 = cross(uv[f[2]] - q, uv[f[0]] - q) / a;
    const double b2 = 1.0 - b0 - b1;
    if (b0 >= -kInsideSlack && b1 >= -kInsideSlack && b2 >= -kInsideSlack) {
      bary = Vec3(b0, b1, b2);
      return t;
    }
  }
  return -1;
}

MeshSurface::MeshSurface(const Mesh& input, const std::string& source)
    : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  s.mesh = weld_mesh(input);
  s.source = source;
  if (s.mesh.triangles.empty()) throw InputError("onto = " + source + ": no triangles");
  const bool file_uv = s.mesh.uv.size() == s.mesh.vertices_mm.size();
  s.uv = file_uv ? s.mesh.uv : lscm_uv(s.mesh, source);
  s.uv_source = file_uv ? "file UVs" : "least-squares conformal (CGAL)";
  normalise_uv(s.mesh, s.uv, !file_uv, source);
  s.build_grid();
  s.build_normals();
  s.measure();
}

MeshSurface::~MeshSurface() = default;

SurfaceFrame MeshSurface::frame_at(const Vec2& uv, double offset_mm) const {
  const Impl& s = *impl_;
  Vec3 b;
  const int t = s.locate(uv, b);
  if (t < 0) throw std::logic_error("MeshSurface::frame_at outside the domain");
  const auto& f = s.mesh.triangles[static_cast<std::size_t>(t)];
  const auto& v = s.mesh.vertices_mm;
  SurfaceFrame fr;
  fr.normal = (b[0] * s.normal[f[0]] + b[1] * s.normal[f[1]] + b[2] * s.normal[f[2]]).normalized();
  fr.point_mm = b[0] * v[f[0]] + b[1] * v[f[1]] + b[2] * v[f[2]] + offset_mm * fr.normal;
  Eigen::Matrix<double, 3, 2> e;
  e << v[f[1]] - v[f[0]], v[f[2]] - v[f[0]];
  Eigen::Matrix2d g;
  g << s.uv[f[1]] - s.uv[f[0]], s.uv[f[2]] - s.uv[f[0]];
  const Eigen::Matrix<double, 3, 2> j = e * g.inverse();
  fr.d_du = j.col(0);
  fr.d_dv = j.col(1);
  return fr;
}

UvBox MeshSurface::domain() const { return impl_->box; }

bool MeshSurface::in_domain(const Vec2& uv) const {
  Vec3 b;
  return impl_->locate(uv, b) >= 0;
}

nlohmann::json MeshSurface::describe() const {
  const Impl& s = *impl_;
  const Box3 b = bounds(s.mesh);
  return {
      {"kind", "mesh"},
      {"source", s.source},
      {"triangles", s.mesh.triangles.size()},
      {"size_mm", {b.size_mm().x(), b.size_mm().y(), b.size_mm().z()}},
      {"uv_source", s.uv_source},
      {"uv_domain_mm", {s.box.min_mm.x(), s.box.min_mm.y(), s.box.max_mm.x(), s.box.max_mm.y()}},
      {"area_ratio_3d_to_uv", {s.distortion.area_ratio_min, s.distortion.area_ratio_max}},
      {"conformal_stretch_max", s.distortion.stretch_max}};
}

TriangleMesh MeshSurface::preview_mesh(double) const { return to_triangle_mesh(impl_->mesh); }
const MapDistortion& MeshSurface::distortion() const { return impl_->distortion; }
const std::string& MeshSurface::uv_source() const { return impl_->uv_source; }
double MeshSurface::top_z_mm() const { return impl_->top_z; }
const Mesh& MeshSurface::mesh() const { return impl_->mesh; }
const std::vector<Vec2>& MeshSurface::vertex_uv() const { return impl_->uv; }

}  // namespace strand::slicer
