// glTF scenes flattened into one triangle mesh (positions, indices, first UV set).
#include "slicer/mesh_gltf.h"

#include <tiny_gltf.h>

#include <Eigen/Geometry>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "slicer/file_io.h"
#include "slicer/input_error.h"

namespace strand::slicer {

namespace {

using Matrix4 = Eigen::Matrix4d;

Matrix4 local_matrix(const tinygltf::Node& n) {
  Matrix4 m = Matrix4::Identity();
  if (n.matrix.size() == 16) {
    for (int i = 0; i < 16; ++i)
      m(i % 4, i / 4) = n.matrix[static_cast<std::size_t>(i)];  // column-major
    return m;
  }
  Eigen::Affine3d a = Eigen::Affine3d::Identity();
  if (n.translation.size() == 3)
    a.translate(Vec3(n.translation[0], n.translation[1], n.translation[2]));
  if (n.rotation.size() == 4) {
    a.rotate(Eigen::Quaterniond(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2])
                 .normalized());
  }
  if (n.scale.size() == 3) a.scale(Vec3(n.scale[0], n.scale[1], n.scale[2]));
  return a.matrix();
}

// Reads element `i` of a float accessor with `components` values per element.
struct FloatReader {
  const unsigned char* base = nullptr;
  std::size_t stride = 0;
  std::size_t count = 0;
  bool ok = false;
};

// The bytes of an accessor: its bufferView inside its buffer, and `count` elements of
// `element` bytes each `stride` apart inside the view; every product checked for overflow.
// Null when anything is out of range.
const unsigned char* accessor_bytes(const tinygltf::Model& g, const tinygltf::Accessor& a,
                                    std::size_t element, std::size_t& stride) {
  if (a.bufferView < 0 || static_cast<std::size_t>(a.bufferView) >= g.bufferViews.size())
    return nullptr;
  const auto& view = g.bufferViews[static_cast<std::size_t>(a.bufferView)];
  if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= g.buffers.size()) return nullptr;
  const auto& buf = g.buffers[static_cast<std::size_t>(view.buffer)];
  const std::size_t size = buf.data.size();
  if (view.byteOffset > size || view.byteLength > size - view.byteOffset) return nullptr;
  stride = view.byteStride ? view.byteStride : element;
  if (stride < element) return nullptr;
  if (a.byteOffset > view.byteLength) return nullptr;
  const std::size_t room = view.byteLength - a.byteOffset;
  if (a.count > 0) {
    if (element > room || (a.count - 1) > (room - element) / stride) return nullptr;
  }
  return buf.data.data() + view.byteOffset + a.byteOffset;
}

FloatReader float_reader(const tinygltf::Model& g, int accessor, int components) {
  FloatReader r;
  if (accessor < 0 || accessor >= static_cast<int>(g.accessors.size())) return r;
  const auto& a = g.accessors[static_cast<std::size_t>(accessor)];
  if (a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT) return r;
  r.base = accessor_bytes(g, a, sizeof(float) * static_cast<std::size_t>(components), r.stride);
  if (!r.base) return r;
  r.count = a.count;
  r.ok = true;
  return r;
}

double float_at(const FloatReader& r, std::size_t i, int c) {
  float f = 0.0f;
  std::memcpy(&f, r.base + i * r.stride + sizeof(float) * static_cast<std::size_t>(c), sizeof f);
  return f;
}

// Indices of a primitive (or 0..count-1 when it has none); empty on a malformed accessor.
std::vector<std::size_t> indices_of(const tinygltf::Model& g, const tinygltf::Primitive& p,
                                    std::size_t vertex_count) {
  std::vector<std::size_t> out;
  if (p.indices < 0) {
    for (std::size_t i = 0; i < vertex_count; ++i) out.push_back(i);
    return out;
  }
  if (static_cast<std::size_t>(p.indices) >= g.accessors.size()) return out;
  const auto& a = g.accessors[static_cast<std::size_t>(p.indices)];
  const int size = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType));
  if (size != 1 && size != 2 && size != 4) return out;
  std::size_t stride = 0;
  const unsigned char* base = accessor_bytes(g, a, static_cast<std::size_t>(size), stride);
  if (!base) return out;
  out.reserve(a.count);
  for (std::size_t i = 0; i < a.count; ++i) {
    const unsigned char* q = base + i * stride;
    std::uint32_t v = 0;
    if (size == 1) v = *q;
    if (size == 2) {
      std::uint16_t s;
      std::memcpy(&s, q, 2);
      v = s;
    }
    if (size == 4) std::memcpy(&v, q, 4);
    if (v >= vertex_count) return {};
    out.push_back(v);
  }
  return out;
}

void add_primitive(const tinygltf::Model& g, const tinygltf::Primitive& p, const Matrix4& xf,
                   const std::string& path, Mesh& m, bool& all_uv) {
  if (p.mode != TINYGLTF_MODE_TRIANGLES && p.mode != -1) return;
  const auto pos_it = p.attributes.find("POSITION");
  if (pos_it == p.attributes.end()) return;
  const FloatReader pos = float_reader(g, pos_it->second, 3);
  if (!pos.ok)
    throw InputError(
        "mesh = " + path +
        ": a POSITION accessor is not float VEC3 data inside its bufferView and buffer");
  const auto uv_it = p.attributes.find("TEXCOORD_0");
  const FloatReader uv =
      uv_it == p.attributes.end() ? FloatReader{} : float_reader(g, uv_it->second, 2);
  all_uv = all_uv && uv.ok && uv.count == pos.count;
  const int base = static_cast<int>(m.vertices_mm.size());
  for (std::size_t i = 0; i < pos.count; ++i) {
    const Eigen::Vector4d v(float_at(pos, i, 0), float_at(pos, i, 1), float_at(pos, i, 2), 1.0);
    m.vertices_mm.push_back((xf * v).head<3>());
    m.uv.push_back(uv.ok && i < uv.count ? Vec2(float_at(uv, i, 0), float_at(uv, i, 1))
                                         : Vec2::Zero());
  }
  const auto idx = indices_of(g, p, pos.count);
  if (idx.size() % 3 != 0 || (idx.empty() && pos.count > 0)) {
    throw InputError("mesh = " + path + ": a triangle index accessor is malformed");
  }
  for (std::size_t i = 0; i + 2 < idx.size(); i += 3) {
    m.triangles.push_back({base + static_cast<int>(idx[i]), base + static_cast<int>(idx[i + 1]),
                           base + static_cast<int>(idx[i + 2])});
  }
}

// Nodes deeper than this are refused: a real scene is a shallow tree.
constexpr int kMaxGltfNodeDepth = 64;

// Each node is visited once (glTF nodes form a strict tree; a node listed twice or in a cycle
// would otherwise multiply the work: a graph fanning out 2^64 times).
void add_node(const tinygltf::Model& g, int node, const Matrix4& parent, int depth,
              const std::string& path, Mesh& m, bool& all_uv, std::vector<char>& visited) {
  if (node < 0 || node >= static_cast<int>(g.nodes.size())) return;
  if (depth > kMaxGltfNodeDepth) {
    throw InputError("mesh = " + path + ": the node tree is deeper than " +
                     std::to_string(kMaxGltfNodeDepth) + " levels");
  }
  if (visited[static_cast<std::size_t>(node)]) return;
  visited[static_cast<std::size_t>(node)] = 1;
  const auto& n = g.nodes[static_cast<std::size_t>(node)];
  const Matrix4 xf = parent * local_matrix(n);
  if (n.mesh >= 0 && n.mesh < static_cast<int>(g.meshes.size())) {
    for (const auto& p : g.meshes[static_cast<std::size_t>(n.mesh)].primitives)
      add_primitive(g, p, xf, path, m, all_uv);
  }
  for (int c : n.children) add_node(g, c, xf, depth + 1, path, m, all_uv, visited);
}

// Files a .gltf names (buffers, images) share the input limit with the .gltf itself.
struct FileBudget {
  std::uintmax_t left = 0;
  std::string path;
  std::string refused;  // why a file was refused, for the message
};

bool read_budgeted(std::vector<unsigned char>* out, std::string* err, const std::string& file,
                   void* user) {
  auto* budget = static_cast<FileBudget*>(user);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) {
    if (err) *err = "cannot read '" + file + "'";
    return false;
  }
  const auto size = std::filesystem::file_size(file, ec);
  if (ec || size > budget->left) {
    budget->refused = "'" + std::filesystem::path(file).filename().string() +
                      "' would take the mesh and the files it names past the " +
                      std::to_string(kMaxInputBytes >> 20) + " MiB input limit";
    if (err) *err = budget->refused;
    return false;
  }
  budget->left -= size;
  std::ifstream in(file, std::ios::binary);
  out->resize(static_cast<std::size_t>(size));
  if (size > 0 &&
      !in.read(reinterpret_cast<char*>(out->data()), static_cast<std::streamsize>(size))) {
    if (err) *err = "cannot read '" + file + "'";
    return false;
  }
  return true;
}

// Images are not needed for a mesh: never decoded.
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int,
                const unsigned char*, int, void*) {
  return true;
}

}  // namespace

Mesh read_gltf(const std::string& path) {
  tinygltf::Model g;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  FileBudget budget;
  std::error_code ec;
  const auto own = std::filesystem::file_size(path, ec);
  budget.left = ec || own > kMaxInputBytes ? 0 : kMaxInputBytes - own;
  budget.path = path;
  tinygltf::FsCallbacks fs{&tinygltf::FileExists, &tinygltf::ExpandFilePath, &read_budgeted,
                           &tinygltf::WriteWholeFile, &budget};
  loader.SetFsCallbacks(fs);
  loader.SetImageLoader(&skip_image, nullptr);
  const bool binary = path.size() >= 4 && (path.substr(path.size() - 4) == ".glb" ||
                                           path.substr(path.size() - 4) == ".GLB");
  const bool ok = binary ? loader.LoadBinaryFromFile(&g, &err, &warn, path)
                         : loader.LoadASCIIFromFile(&g, &err, &warn, path);
  if (!ok && !budget.refused.empty()) {
    throw InputError("mesh = " + path + ": " + budget.refused);
  }
  if (!ok) {
    const auto nl = err.find('\n');
    throw InputError("mesh = " + path + ": cannot read it as glTF" +
                     (err.empty() ? "" : " (" + err.substr(0, nl) + ")"));
  }
  Mesh m;
  bool all_uv = true;
  // glTF is +Y up; parts stand on the bed with +Z up: (x, y, z) -> (x, -z, y).
  Matrix4 y_up_to_z_up = Matrix4::Zero();
  y_up_to_z_up(0, 0) = 1.0, y_up_to_z_up(1, 2) = -1.0, y_up_to_z_up(2, 1) = 1.0,
                  y_up_to_z_up(3, 3) = 1.0;
  std::vector<char> visited(g.nodes.size(), 0);
  const int scene = g.defaultScene >= 0 ? g.defaultScene : 0;
  if (scene < static_cast<int>(g.scenes.size())) {
    for (int n : g.scenes[static_cast<std::size_t>(scene)].nodes)
      add_node(g, n, y_up_to_z_up, 0, path, m, all_uv, visited);
  } else {
    for (std::size_t i = 0; i < g.meshes.size(); ++i) {
      for (const auto& p : g.meshes[i].primitives)
        add_primitive(g, p, y_up_to_z_up, path, m, all_uv);
    }
  }
  if (!all_uv) m.uv.clear();
  return m;
}

}  // namespace strand::slicer
