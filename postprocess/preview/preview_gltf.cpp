// Scene -> tinygltf Model -> GLB bytes.
#include "postprocess/preview/preview_gltf.h"

#include <tiny_gltf.h>

#include <Eigen/Geometry>  // cross products for the tube frames

#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <numbers>
#include <sstream>

namespace strand::post {

namespace {

using Lines = std::map<slicer::Feature, std::vector<float>>;  // xyz pairs per feature

// Opacity of the substrate, low enough that the paths behind it stay readable.
constexpr double kSubstrateAlpha = 0.35;

// One accessor over a new buffer view: float VEC3 (positions, normals) or uint32 SCALAR
// indices; min/max are filled for positions as glTF requires.
template <typename T>
int add_accessor(tinygltf::Model& m, const std::vector<T>& data, bool indices, bool with_bounds) {
  auto& buf = m.buffers[0].data;
  const std::size_t offset = buf.size();
  buf.resize(offset + data.size() * sizeof(T));
  std::memcpy(buf.data() + offset, data.data(), data.size() * sizeof(T));
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = offset;
  view.byteLength = data.size() * sizeof(T);
  view.target = indices ? TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER : TINYGLTF_TARGET_ARRAY_BUFFER;
  m.bufferViews.push_back(view);
  tinygltf::Accessor a;
  a.bufferView = static_cast<int>(m.bufferViews.size()) - 1;
  a.componentType = indices ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT : TINYGLTF_COMPONENT_TYPE_FLOAT;
  a.type = indices ? TINYGLTF_TYPE_SCALAR : TINYGLTF_TYPE_VEC3;
  a.count = indices ? data.size() : data.size() / 3;
  if (with_bounds) {
    a.minValues = {1e30, 1e30, 1e30};
    a.maxValues = {-1e30, -1e30, -1e30};
    for (std::size_t i = 0; i < data.size(); ++i) {
      a.minValues[i % 3] = std::min(a.minValues[i % 3], static_cast<double>(data[i]));
      a.maxValues[i % 3] = std::max(a.maxValues[i % 3], static_cast<double>(data[i]));
    }
  }
  m.accessors.push_back(a);
  return static_cast<int>(m.accessors.size()) - 1;
}

struct Tubes {
  std::vector<float> positions, normals;
  std::vector<std::uint32_t> indices;
};

void push3(std::vector<float>& v, const slicer::Vec3& p) {
  for (int k = 0; k < 3; ++k) v.push_back(static_cast<float>(p[k]));
}

// A prism of `sides` faces around segment a-b (no end caps: neighbours overlap at joints).
void add_tube(Tubes& t, const slicer::Vec3& a, const slicer::Vec3& b, double radius, int sides) {
  const slicer::Vec3 d = b - a;
  if (d.norm() < 1e-9) return;
  const slicer::Vec3 axis = d.normalized();
  const slicer::Vec3 helper = std::abs(axis.z()) < 0.9 ? slicer::Vec3::UnitZ() : slicer::Vec3::UnitX();
  const slicer::Vec3 u = axis.cross(helper).normalized(), v = axis.cross(u);
  const auto base = static_cast<std::uint32_t>(t.positions.size() / 3);
  for (int k = 0; k < sides; ++k) {
    const double ang = 2.0 * std::numbers::pi * k / sides;
    const slicer::Vec3 n = std::cos(ang) * u + std::sin(ang) * v;
    push3(t.positions, a + radius * n);
    push3(t.positions, b + radius * n);
    push3(t.normals, n);
    push3(t.normals, n);
  }
  const auto s = static_cast<std::uint32_t>(sides);
  for (std::uint32_t k = 0; k < s; ++k) {
    const std::uint32_t a0 = base + 2 * k, b0 = a0 + 1, a1 = base + 2 * ((k + 1) % s), b1 = a1 + 1;
    t.indices.insert(t.indices.end(), {a0, a1, b1, a0, b1, b0});
  }
}

tinygltf::Primitive tube_primitive(tinygltf::Model& m, const std::vector<float>& pairs, double radius, int sides) {
  Tubes t;
  for (std::size_t i = 0; i + 5 < pairs.size(); i += 6) {
    add_tube(t, {pairs[i], pairs[i + 1], pairs[i + 2]}, {pairs[i + 3], pairs[i + 4], pairs[i + 5]}, radius, sides);
  }
  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.attributes["POSITION"] = add_accessor(m, t.positions, false, true);
  prim.attributes["NORMAL"] = add_accessor(m, t.normals, false, false);
  prim.indices = add_accessor(m, t.indices, true, false);
  return prim;
}

int material_for(tinygltf::Model& m, std::map<slicer::Feature, int>& made, slicer::Feature f) {
  if (auto it = made.find(f); it != made.end()) return it->second;
  tinygltf::Material mat;
  mat.name = slicer::to_string(f);
  const Rgb c = feature_colour(f);
  mat.pbrMetallicRoughness.baseColorFactor = {c.r, c.g, c.b, 1.0};
  mat.pbrMetallicRoughness.metallicFactor = 0.0;
  mat.pbrMetallicRoughness.roughnessFactor = 1.0;
  m.materials.push_back(mat);
  return made[f] = static_cast<int>(m.materials.size()) - 1;
}

// The substrate as one translucent, double-sided mesh with smooth normals (face normals
// averaged at shared vertices), so the path tubes show through it.
tinygltf::Mesh substrate_mesh(tinygltf::Model& m, const slicer::TriangleMesh& t) {
  std::vector<float> positions, normals;
  std::vector<slicer::Vec3> sum(t.vertices_mm.size(), slicer::Vec3::Zero());
  std::vector<std::uint32_t> indices;
  for (const auto& tri : t.triangles) {
    const auto& a = t.vertices_mm[static_cast<std::size_t>(tri[0])];
    const slicer::Vec3 n = (t.vertices_mm[static_cast<std::size_t>(tri[1])] - a)
                               .cross(t.vertices_mm[static_cast<std::size_t>(tri[2])] - a);
    for (int k : tri) {
      sum[static_cast<std::size_t>(k)] += n;
      indices.push_back(static_cast<std::uint32_t>(k));
    }
  }
  for (std::size_t i = 0; i < t.vertices_mm.size(); ++i) {
    push3(positions, t.vertices_mm[i]);
    push3(normals, sum[i].norm() > 0 ? slicer::Vec3(sum[i].normalized()) : slicer::Vec3::UnitZ());
  }
  tinygltf::Material mat;
  mat.name = "substrate";
  mat.alphaMode = "BLEND";
  mat.doubleSided = true;
  mat.pbrMetallicRoughness.baseColorFactor = {0.62, 0.66, 0.72, kSubstrateAlpha};
  mat.pbrMetallicRoughness.metallicFactor = 0.0;
  mat.pbrMetallicRoughness.roughnessFactor = 1.0;
  m.materials.push_back(mat);
  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.attributes["POSITION"] = add_accessor(m, positions, false, true);
  prim.attributes["NORMAL"] = add_accessor(m, normals, false, false);
  prim.indices = add_accessor(m, indices, true, false);
  prim.material = static_cast<int>(m.materials.size()) - 1;
  tinygltf::Mesh mesh;
  mesh.name = "substrate";
  mesh.primitives.push_back(prim);
  return mesh;
}

void add_child(tinygltf::Model& m, tinygltf::Mesh mesh) {
  m.meshes.push_back(std::move(mesh));
  tinygltf::Node node;
  node.name = m.meshes.back().name;
  node.mesh = static_cast<int>(m.meshes.size()) - 1;
  m.nodes.push_back(node);
  m.nodes[0].children.push_back(static_cast<int>(m.nodes.size()) - 1);
}

std::map<int, Lines> lines_by_layer(const PreviewScene& s) {
  std::map<int, Lines> layers;
  for (const auto& p : s.paths) {
    if (p.travel) continue;
    auto& xyz = layers[p.layer][p.feature];
    for (std::size_t i = 1; i < p.points_mm.size(); ++i) {
      for (const auto* q : {&p.points_mm[i - 1], &p.points_mm[i]}) {
        xyz.push_back(static_cast<float>(q->x()));
        xyz.push_back(static_cast<float>(q->y()));
        xyz.push_back(static_cast<float>(q->z()));
      }
    }
  }
  return layers;
}

}  // namespace

std::string render_glb(const PreviewScene& scene, const GlbOptions& o) {
  const double radius = 0.5 * (scene.bead_width_mm > 0 ? scene.bead_width_mm : 0.4);
  tinygltf::Model m;
  m.asset.version = "2.0";
  m.asset.generator = "Strand preview";
  m.buffers.emplace_back();
  tinygltf::Node root;
  root.name = "toolpath";
  root.scale = {0.001, 0.001, 0.001};              // mm -> m
  root.rotation = {-std::sqrt(0.5), 0.0, 0.0, std::sqrt(0.5)};  // z-up -> y-up
  m.nodes.push_back(root);
  std::map<slicer::Feature, int> materials;
  if (!scene.substrate.triangles.empty()) add_child(m, substrate_mesh(m, scene.substrate));
  for (const auto& [layer, lines] : lines_by_layer(scene)) {
    tinygltf::Mesh mesh;
    mesh.name = "layer " + std::to_string(layer);
    for (const auto& [feature, xyz] : lines) {
      if (xyz.empty()) continue;
      tinygltf::Primitive prim;
      if (o.tubes) {
        prim = tube_primitive(m, xyz, radius, o.tube_sides);
      } else {
        prim.mode = TINYGLTF_MODE_LINE;
        prim.attributes["POSITION"] = add_accessor(m, xyz, false, true);
      }
      prim.material = material_for(m, materials, feature);
      mesh.primitives.push_back(prim);
    }
    add_child(m, std::move(mesh));
  }
  tinygltf::Scene sc;
  sc.name = "Strand";
  sc.nodes = {0};
  m.scenes.push_back(sc);
  m.defaultScene = 0;
  std::ostringstream out;
  tinygltf::TinyGLTF writer;
  writer.WriteGltfSceneToStream(&m, out, false, true);
  return out.str();
}

}  // namespace strand::post
