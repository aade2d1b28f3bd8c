// Mesh files to Mesh: OpenMesh for STL/OBJ/PLY/OFF, tinygltf for glTF/GLB, then placement.
#include "slicer/mesh_io.h"

#include <Eigen/Geometry>
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>

#include "slicer/file_io.h"
#include "slicer/input_error.h"
#include "slicer/mesh_3mf.h"
#include "slicer/mesh_gltf.h"
#include "slicer/mesh_header.h"
#include "slicer/units.h"

namespace strand::slicer {

namespace {

struct DoubleTraits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
};
using OmMesh = OpenMesh::TriMesh_ArrayKernelT<DoubleTraits>;

std::string extension_of(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext;
}

// OpenMesh reports through its own streams; library code never prints.
void silence_openmesh() {
  omerr().disable();
  omout().disable();
  omlog().disable();
}

Mesh read_openmesh(const std::string& path, const std::string& ext) {
  silence_openmesh();
  OmMesh om;
  om.request_vertex_texcoords2D();
  OpenMesh::IO::Options opt = OpenMesh::IO::Options::VertexTexCoord;
  // OpenMesh picks its reader by the extension, in either case.
  if (!OpenMesh::IO::read_mesh(om, path, opt)) {
    throw InputError("mesh = " + path + ": cannot read it as " + ext.substr(1) +
                     " (damaged or not a mesh file)");
  }
  Mesh m;
  m.vertices_mm.reserve(om.n_vertices());
  for (const auto& v : om.vertices()) {
    const auto& p = om.point(v);
    m.vertices_mm.emplace_back(p[0], p[1], p[2]);
  }
  // The STL reader leaves the requested flag set without reading any: STL has no UVs.
  if (ext != ".stl" && opt.check(OpenMesh::IO::Options::VertexTexCoord)) {
    for (const auto& v : om.vertices()) {
      const auto& t = om.texcoord2D(v);
      m.uv.emplace_back(t[0], t[1]);
    }
  }
  m.triangles.reserve(om.n_faces());
  for (const auto& f : om.faces()) {
    std::array<int, 3> tri{};
    int k = 0;
    for (const auto& v : f.vertices()) tri[static_cast<std::size_t>(k++)] = v.idx();
    m.triangles.push_back(tri);
  }
  return m;
}

void check_content(const Mesh& m, const std::string& path) {
  if (m.triangles.empty()) throw InputError("mesh = " + path + ": no triangles in the file");
  if (m.triangles.size() > kMaxMeshTriangles) {
    throw InputError("mesh = " + path + ": " + std::to_string(m.triangles.size()) +
                     " triangles; at most " + std::to_string(kMaxMeshTriangles) + " are accepted");
  }
  for (std::size_t i = 0; i < m.vertices_mm.size(); ++i) {
    if (!m.vertices_mm[i].allFinite()) {
      throw InputError("mesh = " + path + ": vertex " + std::to_string(i) +
                       " has a non-finite coordinate (NaN or infinity)");
    }
  }
  for (const Vec2& t : m.uv) {
    if (!t.allFinite()) throw InputError("mesh = " + path + ": a texture coordinate is not finite");
  }
}

// The file exists, is not empty and within kMaxInputBytes; its size in bytes.
std::uintmax_t vet_file(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw InputError("mesh = " + path + ": no such file");
  const auto size = fs::file_size(path, ec);
  if (ec) throw InputError("mesh = " + path + ": cannot read the file");
  if (size == 0) throw InputError("mesh = " + path + ": the file is empty");
  if (size > kMaxInputBytes) {
    throw InputError("mesh = " + path + ": " + std::to_string(size >> 20) +
                     " MiB, larger than the " + std::to_string(kMaxInputBytes >> 20) +
                     " MiB limit");
  }
  return size;
}

}  // namespace

Mesh read_mesh_file(const std::string& path) {
  const auto size = vet_file(path);
  const std::string ext = extension_of(path);
  Mesh m;
  if (ext == ".gltf" || ext == ".glb") {
    m = read_gltf(path);
  } else if (ext == ".3mf") {
    m = read_3mf(path);
  } else if (ext == ".stl" || ext == ".obj" || ext == ".ply" || ext == ".off") {
    if (ext == ".ply") vet_ply_header(path, size);
    vet_finite_vertices(path, ext, size);  // before the OFF check: NaN is named as such
    if (ext == ".off") vet_off_file(path);
    if (ext == ".obj") vet_obj_faces(path);
    m = read_openmesh(path, ext);
  } else {
    throw InputError("mesh = " + path + ": unknown format '" + ext +
                     "' (allowed: .stl, .obj, .ply, .off, .gltf, .glb, .3mf)");
  }
  check_content(m, path);
  return m;
}

std::vector<Mesh> read_mesh_objects(const std::string& path) {
  if (extension_of(path) != ".3mf") return {read_mesh_file(path)};
  vet_file(path);
  std::vector<Mesh> objects = read_3mf_objects(path);
  for (const Mesh& m : objects) check_content(m, path);
  return objects;
}

Mesh merge_meshes(const std::vector<Mesh>& meshes) {
  Mesh out;
  for (const Mesh& m : meshes) {
    const auto base = static_cast<int>(out.vertices_mm.size());
    out.vertices_mm.insert(out.vertices_mm.end(), m.vertices_mm.begin(), m.vertices_mm.end());
    for (const auto& t : m.triangles) out.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  }
  return out;
}

std::vector<Mesh> split_mesh(const Mesh& merged, const std::vector<Mesh>& like) {
  std::vector<Mesh> out;
  std::size_t v = 0;
  for (const Mesh& m : like) {
    Mesh piece = m;
    for (Vec3& p : piece.vertices_mm) p = merged.vertices_mm.at(v++);
    out.push_back(std::move(piece));
  }
  return out;
}

double mm_per_mesh_unit(const std::string& key, const std::string& units) {
  if (units == "mm") return 1.0;
  if (units == "cm") return kMmPerCm;
  if (units == "m") return kMmPerM;
  if (units == "in") return kMmPerInch;
  throw InputError(key + " = " + units + ": must be one of mm, cm, m, in");
}

Placement placement_from(const std::string& key, const std::string& name) {
  if (name == "center") return Placement::Center;
  if (name == "origin") return Placement::Origin;
  throw InputError(key + " = " + name + ": must be center or origin");
}

Mesh place_mesh(Mesh m, const MeshPlacement& p, Eigen::Affine3d* applied) {
  const Eigen::Matrix3d r = (Eigen::AngleAxisd(deg_to_rad(p.rotate_deg.z()), Vec3::UnitZ()) *
                             Eigen::AngleAxisd(deg_to_rad(p.rotate_deg.y()), Vec3::UnitY()) *
                             Eigen::AngleAxisd(deg_to_rad(p.rotate_deg.x()), Vec3::UnitX()))
                                .toRotationMatrix();
  for (Vec3& v : m.vertices_mm) v = r * (v * p.mm_per_unit);
  const Box3 b = bounds(m);
  Vec3 shift(0.0, 0.0, -b.min_mm.z());
  if (p.place == Placement::Center) {
    shift.x() = -(b.min_mm.x() + b.max_mm.x()) / 2.0;
    shift.y() = -(b.min_mm.y() + b.max_mm.y()) / 2.0;
  }
  for (Vec3& v : m.vertices_mm) v += shift;
  if (applied) {
    applied->setIdentity();
    applied->linear() = r * p.mm_per_unit;
    applied->translation() = shift;
  }
  return m;
}

std::string binary_stl_bytes(const Mesh& m) {
  std::string out(80, '\0');
  const std::string head = "binary STL written by strand";
  out.replace(0, head.size(), head);
  const auto n = static_cast<std::uint32_t>(m.triangles.size());
  out.append(reinterpret_cast<const char*>(&n), 4);
  for (const auto& t : m.triangles) {
    const Vec3& a = m.vertices_mm[static_cast<std::size_t>(t[0])];
    const Vec3& b = m.vertices_mm[static_cast<std::size_t>(t[1])];
    const Vec3& c = m.vertices_mm[static_cast<std::size_t>(t[2])];
    Vec3 normal = (b - a).cross(c - a);
    if (normal.norm() > 0.0) normal.normalize();
    float f[12];
    for (int k = 0; k < 3; ++k) {
      f[k] = static_cast<float>(normal[k]);
      f[3 + k] = static_cast<float>(a[k]);
      f[6 + k] = static_cast<float>(b[k]);
      f[9 + k] = static_cast<float>(c[k]);
    }
    out.append(reinterpret_cast<const char*>(f), sizeof f);
    out.append(2, '\0');
  }
  return out;
}

}  // namespace strand::slicer
