// Robot-held mesh substrates: the map made facing +z, frames turned back into the workpiece
// frame, points mapped back by closest points, and the record beside a pose CSV.
#include "slicer/mesh_substrate.h"

#include <Eigen/Geometry>
#include <cstdint>
#include <cstdio>
#include <filesystem>

#include "slicer/input_error.h"
#include "slicer/mesh_check.h"

namespace strand::slicer {

namespace {

const std::string kOntoPrefix = "onto = ";

// MeshSurface names its input "onto = FILE" (the 3-axis drape's flag): this one is the
// substrate's mesh.
InputError renamed(const InputError& e, const std::string& source) {
  std::string m = e.what();
  if (m.rfind(kOntoPrefix, 0) == 0)
    m = "substrate.mesh = " + m.substr(kOntoPrefix.size());
  else
    m = "substrate.mesh = " + source + ": " + m;
  return InputError(m);
}

// Rows: the map frame's x, y, z in the workpiece frame (z = facing; y = the workpiece z axis
// made perpendicular to it, or the workpiece y axis when z is the facing).
Eigen::Matrix3d map_frame(const Vec3& facing) {
  Vec3 y = Vec3::UnitZ() - Vec3::UnitZ().dot(facing) * facing;
  if (y.norm() < 1e-6) y = Vec3::UnitY() - Vec3::UnitY().dot(facing) * facing;
  y.normalize();
  Eigen::Matrix3d q;
  q.row(0) = y.cross(facing).transpose();
  q.row(1) = y.transpose();
  q.row(2) = facing.transpose();
  return q;
}

}  // namespace

struct MeshSubstrate::Impl {
  std::string source;
  Vec3 facing = Vec3::UnitZ();
  Eigen::Matrix3d q = Eigen::Matrix3d::Identity();  // workpiece -> map frame
  std::unique_ptr<MeshSurface> surface;             // made in the map frame
  Mesh mesh;                                        // welded, workpiece frame
  std::vector<Vec3> normal;                         // per vertex, unit, outward
  std::unique_ptr<MeshProximity> proximity;
  Vec3 centre = Vec3::Zero();  // of the bounding box
  double diagonal_mm = 0.0;

  Located located(const MeshPoint& m, double offset, const std::vector<Vec2>& uv) const {
    Located out;
    out.base_mm = m.point_mm;
    out.normal = normal_at(m);
    out.offset_mm = offset;
    const auto& t = mesh.triangles[static_cast<std::size_t>(m.triangle)];
    out.uv_mm =
        m.barycentric[0] * uv[t[0]] + m.barycentric[1] * uv[t[1]] + m.barycentric[2] * uv[t[2]];
    return out;
  }

  Vec3 normal_at(const MeshPoint& m) const {
    const auto& t = mesh.triangles[static_cast<std::size_t>(m.triangle)];
    const Vec3 n = m.barycentric[0] * normal[t[0]] + m.barycentric[1] * normal[t[1]] +
                   m.barycentric[2] * normal[t[2]];
    return n.norm() > 0 ? n.normalized() : facing;
  }
};

MeshSubstrate::MeshSubstrate(const Mesh& input, const std::string& source)
    : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  s.source = source;
  Mesh welded = weld_mesh(input);
  if (welded.triangles.empty()) throw InputError("substrate.mesh = " + source + ": no triangles");
  Vec3 sum = Vec3::Zero();
  double area = 0.0;
  for (const auto& t : welded.triangles) {
    const Vec3 n = (welded.vertices_mm[t[1]] - welded.vertices_mm[t[0]])
                       .cross(welded.vertices_mm[t[2]] - welded.vertices_mm[t[0]]);
    sum += n;
    area += n.norm();
  }
  // A closed mesh's outward normals cancel: it has no side that could face a fixed nozzle
  // as one patch.
  if (!(sum.norm() > 0.05 * area)) {
    throw InputError("substrate.mesh = " + source +
                     ": its outside faces every way (a closed or nearly closed mesh); give the "
                     "patch to print on, open, with its outside (counter-clockwise side) "
                     "towards the nozzle");
  }
  s.facing = sum.normalized();
  s.q = map_frame(s.facing);
  Mesh turned = welded;
  for (Vec3& v : turned.vertices_mm) v = s.q * v;
  try {
    s.surface = std::make_unique<MeshSurface>(turned, source);
  } catch (const InputError& e) {
    throw renamed(e, source);
  }
  s.mesh = s.surface->mesh();
  for (Vec3& v : s.mesh.vertices_mm) v = s.q.transpose() * v;
  s.normal.assign(s.mesh.vertices_mm.size(), Vec3::Zero());
  for (const auto& f : s.mesh.triangles) {
    const Vec3 n = (s.mesh.vertices_mm[f[1]] - s.mesh.vertices_mm[f[0]])
                       .cross(s.mesh.vertices_mm[f[2]] - s.mesh.vertices_mm[f[0]]);
    for (int k = 0; k < 3; ++k) s.normal[f[k]] += n;  // area-weighted, as MeshSurface
  }
  for (Vec3& n : s.normal) n = n.norm() > 0 ? Vec3(n.normalized()) : s.facing;
  s.proximity = std::make_unique<MeshProximity>(s.mesh);
  const Box3 box = bounds(s.mesh);
  s.centre = (box.min_mm + box.max_mm) / 2.0;
  s.diagonal_mm = box.size_mm().norm();
}

MeshSubstrate::~MeshSubstrate() = default;

SurfaceFrame MeshSubstrate::frame_at(const Vec2& uv, double offset_mm) const {
  const Impl& s = *impl_;
  if (!s.surface->in_domain(uv)) {  // sampling a curve may look beyond its end points
    const UvBox b = s.surface->domain();
    char text[256];
    std::snprintf(text, sizeof text,
                  ": the pattern leaves the mesh at pattern point (u, v) = (%.3f, %.3f) mm; the "
                  "mesh's (u, v) spans %.3f..%.3f x %.3f..%.3f mm: use a smaller pattern or a "
                  "larger mesh",
                  uv.x(), uv.y(), b.min_mm.x(), b.max_mm.x(), b.min_mm.y(), b.max_mm.y());
    throw InputError("substrate.mesh = " + s.source + text);
  }
  SurfaceFrame f = s.surface->frame_at(uv, offset_mm);
  const Eigen::Matrix3d back = s.q.transpose();
  f.point_mm = back * f.point_mm;
  f.normal = back * f.normal;
  f.d_du = back * f.d_du;
  f.d_dv = back * f.d_dv;
  return f;
}

UvBox MeshSubstrate::domain() const { return impl_->surface->domain(); }
bool MeshSubstrate::in_domain(const Vec2& uv) const { return impl_->surface->in_domain(uv); }

nlohmann::json MeshSubstrate::describe() const {
  const Impl& s = *impl_;
  nlohmann::json j = s.surface->describe();
  const Box3 b = bounds(s.mesh);
  j["size_mm"] = {b.size_mm().x(), b.size_mm().y(), b.size_mm().z()};
  j["bounds_mm"] = {b.min_mm.x(), b.min_mm.y(), b.min_mm.z(),
                    b.max_mm.x(), b.max_mm.y(), b.max_mm.z()};
  j["facing"] = {s.facing.x(), s.facing.y(), s.facing.z()};
  j["frame"] = "the mesh file's coordinates (mm) are the workpiece frame on the flange";
  return j;
}

TriangleMesh MeshSubstrate::preview_mesh(double) const { return to_triangle_mesh(impl_->mesh); }
const MapDistortion& MeshSubstrate::distortion() const { return impl_->surface->distortion(); }
const std::string& MeshSubstrate::uv_source() const { return impl_->surface->uv_source(); }
const std::string& MeshSubstrate::source() const { return impl_->source; }
const Vec3& MeshSubstrate::facing() const { return impl_->facing; }
const Eigen::Matrix3d& MeshSubstrate::map_rotation() const { return impl_->q; }
const Mesh& MeshSubstrate::mesh() const { return impl_->mesh; }

MeshSubstrate::Located MeshSubstrate::locate(const Vec3& p) const {
  const Impl& s = *impl_;
  // Fixed point of base = closest(p - offset * normal(base)): converges while the offset
  // is small next to the surface's radius of curvature (the normals turn slowly).
  MeshPoint m = s.proximity->closest(p);
  Vec3 n = s.normal_at(m);
  double offset = (p - m.point_mm).dot(n);
  for (int i = 0; i < 12; ++i) {
    const MeshPoint next = s.proximity->closest(p - offset * n);
    const bool settled = (next.point_mm - m.point_mm).norm() < 1e-9;
    m = next;
    n = s.normal_at(m);
    offset = (p - m.point_mm).dot(n);
    if (settled) break;
  }
  Located out;
  out.base_mm = m.point_mm;
  out.normal = n;
  out.offset_mm = offset;
  out.residual_mm = (p - (m.point_mm + offset * n)).norm();
  const auto& t = s.mesh.triangles[static_cast<std::size_t>(m.triangle)];
  const auto& uv = s.surface->vertex_uv();
  out.uv_mm =
      m.barycentric[0] * uv[t[0]] + m.barycentric[1] * uv[t[1]] + m.barycentric[2] * uv[t[2]];
  return out;
}

std::optional<MeshSubstrate::Located> MeshSubstrate::foot_along(const Vec3& p,
                                                                const Vec3& n) const {
  const Impl& s = *impl_;
  const double reach = (p - s.centre).norm() + s.diagonal_mm + 1.0;
  const Vec3 u = n.normalized();
  if (const auto below = s.proximity->first_hit(p, p - reach * u))
    return s.located(*below, below->distance_mm, s.surface->vertex_uv());
  if (const auto above = s.proximity->first_hit(p, p + reach * u))
    return s.located(*above, -above->distance_mm, s.surface->vertex_uv());
  return std::nullopt;
}

double MeshSubstrate::distance_mm(const Vec3& p) const {
  return impl_->proximity->closest(p).distance_mm;
}

std::optional<Vec3> MeshSubstrate::cone_hit(const NozzleCone& cone, const Vec3& tip,
                                            const Vec3& up) const {
  return impl_->proximity->cone_hit(cone, tip, up);
}

std::string content_fingerprint(std::string_view bytes) {
  std::uint64_t h = 14695981039346656037ull;
  for (const unsigned char c : bytes) {
    h ^= c;
    h *= 1099511628211ull;
  }
  static const char* const kHex = "0123456789abcdef";
  std::string out(16, '0');
  for (int i = 15; i >= 0; --i, h >>= 4) out[static_cast<std::size_t>(i)] = kHex[h & 0xf];
  return out;
}

nlohmann::json to_json(const MeshSubstrateRecord& r) {
  return {{"substrate", "mesh"},
          {"mesh", r.mesh},
          {"fnv1a", r.fingerprint},
          {"machine", r.machine},
          {"layer_offsets_mm", r.layer_offsets_mm},
          {"nozzle_cone",
           {{"half_angle_deg", r.cone.half_angle_deg},
            {"length_mm", r.cone.length_mm},
            {"tip_radius_mm", r.cone.tip_radius_mm}}},
          {"note",
           "written by strand beside the pose CSV: the mesh its contact points lie on (strand "
           "check and strand preview read it)"}};
}

MeshSubstrateRecord mesh_record_from_json(const nlohmann::json& j, const std::string& file) {
  const auto bad = [&](const std::string& key, const std::string& what) {
    return InputError("input = " + file + ": " + key + " " + what +
                      " (a substrate record written by strand beside its pose CSV)");
  };
  if (!j.is_object() || j.value("substrate", "") != "mesh")
    throw bad("substrate", "must be \"mesh\"");
  MeshSubstrateRecord r;
  for (const char* key : {"mesh", "fnv1a", "machine"}) {
    if (!j.contains(key) || !j.at(key).is_string()) throw bad(key, "must be text");
  }
  r.mesh = j.at("mesh").get<std::string>();
  r.fingerprint = j.at("fnv1a").get<std::string>();
  r.machine = j.at("machine").get<std::string>();
  if (!j.contains("layer_offsets_mm") || !j.at("layer_offsets_mm").is_array())
    throw bad("layer_offsets_mm", "must be a list of numbers");
  for (const auto& v : j.at("layer_offsets_mm")) {
    if (!v.is_number()) throw bad("layer_offsets_mm", "must be a list of numbers");
    r.layer_offsets_mm.push_back(v.get<double>());
  }
  if (j.contains("nozzle_cone") && j.at("nozzle_cone").is_object()) {
    const auto& c = j.at("nozzle_cone");
    r.cone.half_angle_deg = c.value("half_angle_deg", r.cone.half_angle_deg);
    r.cone.length_mm = c.value("length_mm", r.cone.length_mm);
    r.cone.tip_radius_mm = c.value("tip_radius_mm", r.cone.tip_radius_mm);
  }
  return r;
}

std::string mesh_record_path(const std::string& csv_path) {
  const std::string base = csv_path.size() > 4 && csv_path.ends_with(".csv")
                               ? csv_path.substr(0, csv_path.size() - 4)
                               : csv_path;
  return base + ".substrate.json";
}

std::string mesh_path_from_record(const MeshSubstrateRecord& r, const std::string& csv_path) {
  const std::filesystem::path mesh(r.mesh);
  if (mesh.is_absolute()) return r.mesh;
  return (std::filesystem::path(csv_path).parent_path() / mesh).lexically_normal().string();
}

}  // namespace strand::slicer
