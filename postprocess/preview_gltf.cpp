// Scene -> tinygltf Model -> GLB bytes.
#include "postprocess/preview_gltf.h"

#include <tiny_gltf.h>

#include <cmath>
#include <cstring>
#include <map>
#include <sstream>

namespace strand::post {

namespace {

using Lines = std::map<slicer::Feature, std::vector<float>>;  // xyz pairs per feature

// One accessor over a new buffer view of float xyz positions.
int add_positions(tinygltf::Model& m, const std::vector<float>& xyz) {
  auto& buf = m.buffers[0].data;
  const std::size_t offset = buf.size();
  buf.resize(offset + xyz.size() * sizeof(float));
  std::memcpy(buf.data() + offset, xyz.data(), xyz.size() * sizeof(float));
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = offset;
  view.byteLength = xyz.size() * sizeof(float);
  view.target = TINYGLTF_TARGET_ARRAY_BUFFER;
  m.bufferViews.push_back(view);
  tinygltf::Accessor a;
  a.bufferView = static_cast<int>(m.bufferViews.size()) - 1;
  a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  a.type = TINYGLTF_TYPE_VEC3;
  a.count = xyz.size() / 3;
  a.minValues = {1e30, 1e30, 1e30};
  a.maxValues = {-1e30, -1e30, -1e30};
  for (std::size_t i = 0; i < xyz.size(); ++i) {
    a.minValues[i % 3] = std::min(a.minValues[i % 3], static_cast<double>(xyz[i]));
    a.maxValues[i % 3] = std::max(a.maxValues[i % 3], static_cast<double>(xyz[i]));
  }
  m.accessors.push_back(a);
  return static_cast<int>(m.accessors.size()) - 1;
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

std::string render_glb(const PreviewScene& scene) {
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
  for (const auto& [layer, lines] : lines_by_layer(scene)) {
    tinygltf::Mesh mesh;
    mesh.name = "layer " + std::to_string(layer);
    for (const auto& [feature, xyz] : lines) {
      if (xyz.empty()) continue;
      tinygltf::Primitive prim;
      prim.mode = TINYGLTF_MODE_LINE;
      prim.attributes["POSITION"] = add_positions(m, xyz);
      prim.material = material_for(m, materials, feature);
      mesh.primitives.push_back(prim);
    }
    m.meshes.push_back(mesh);
    tinygltf::Node node;
    node.name = mesh.name;
    node.mesh = static_cast<int>(m.meshes.size()) - 1;
    m.nodes.push_back(node);
    m.nodes[0].children.push_back(static_cast<int>(m.nodes.size()) - 1);
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
