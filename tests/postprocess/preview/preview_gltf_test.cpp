// GLB preview: loads back with tinygltf; one node per deposited layer under a root.
#include "postprocess/preview/preview_gltf.h"

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <cmath>

#include "patterns/registry.h"
#include "postprocess/inspect/gcode_parser.h"
#include "slicer/params.h"
#include "tests/support/cylinder_scene.h"

namespace strand::post {
namespace {

// Three layers: 4 + 2 + 1 deposit segments; layer 1 has two features.
const char* kThreeLayers =
    ";LAYER:0\nG0 X0 Y0 Z0.5\nG1 X20 Y0 E1\nG1 X20 Y20 E2\nG1 X0 Y20 E3\nG1 X0 Y0 E4\n"
    ";LAYER:1\n;TYPE:Solid infill\n;FEATURE:infill\nG0 X0 Y0 Z1\nG1 X10 Y0 E5\n"
    ";TYPE:Perimeter\n;FEATURE:wall\nG1 X10 Y10 E6\n"
    ";LAYER:2\nG0 X0 Y0 Z1.5\nG1 X5 Y5 E7\n";

tinygltf::Model load(const std::string& glb) {
  tinygltf::Model m;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  const bool ok = loader.LoadBinaryFromMemory(&m, &err, &warn, reinterpret_cast<const unsigned char*>(glb.data()),
                                              static_cast<unsigned int>(glb.size()));
  EXPECT_TRUE(ok) << err;
  return m;
}

TEST(PreviewGltf, SubstrateIsATranslucentNodeUnderThePathTubes) {
  const auto* g = patterns::find_generator("tetrachiral");
  const auto t = g->generate_wrapped(
      slicer::resolve_params(g->table(), {{"nozzle", 0.5}, {"cell", 10}, {"rows", 2}, {"layers", 2}}),
      2 * M_PI * 12);
  const auto scene = strand::testing::cylinder_scene(t, 12.0, 40.0);
  const auto m = load(render_glb(scene));
  const auto& root = m.nodes.at(0);
  ASSERT_EQ(root.children.size(), 3u) << "substrate + 2 layers";
  const auto& node = m.nodes.at(static_cast<std::size_t>(root.children[0]));
  EXPECT_EQ(node.name, "substrate");
  const auto& prim = m.meshes.at(static_cast<std::size_t>(node.mesh)).primitives.at(0);
  const auto& mat = m.materials.at(static_cast<std::size_t>(prim.material));
  EXPECT_EQ(mat.alphaMode, "BLEND");
  EXPECT_TRUE(mat.doubleSided);
  EXPECT_LT(mat.pbrMetallicRoughness.baseColorFactor.at(3), 1.0);
  EXPECT_GT(mat.pbrMetallicRoughness.baseColorFactor.at(3), 0.0);
  const auto& pos = m.accessors.at(static_cast<std::size_t>(prim.attributes.at("POSITION")));
  EXPECT_EQ(pos.count, scene.substrate.vertices_mm.size());
  EXPECT_EQ(m.accessors.at(static_cast<std::size_t>(prim.indices)).count,
            3 * scene.substrate.triangles.size());
  EXPECT_NEAR(pos.maxValues.at(0), 20.0, 1e-4) << "the cylinder's end, mm";
  for (int k : root.children) {
    if (k == root.children[0]) continue;
    const auto& layer = m.meshes.at(static_cast<std::size_t>(m.nodes.at(static_cast<std::size_t>(k)).mesh));
    for (const auto& p : layer.primitives) {
      EXPECT_EQ(m.materials.at(static_cast<std::size_t>(p.material)).alphaMode, "OPAQUE");
    }
  }
}

TEST(PreviewGltf, LoadsBackWithARootAndOneNodePerLayer) {
  const auto m = load(render_glb(preview_scene(parse_gcode(kThreeLayers).program, 0.01)));
  ASSERT_EQ(m.nodes.size(), 4u);
  EXPECT_EQ(m.nodes[0].children.size(), 3u);
  ASSERT_EQ(m.scenes.size(), 1u);
  EXPECT_EQ(m.scenes[0].nodes, std::vector<int>{0});
  EXPECT_EQ(m.nodes[0].scale, (std::vector<double>{0.001, 0.001, 0.001}));
}

TEST(PreviewGltf, LinesOptionGivesLinePairsColouredByFeature) {
  const auto m = load(render_glb(preview_scene(parse_gcode(kThreeLayers).program, 0.01), {.tubes = false}));
  std::size_t vertices = 0;
  for (const auto& mesh : m.meshes) {
    for (const auto& p : mesh.primitives) {
      EXPECT_EQ(p.mode, TINYGLTF_MODE_LINE);
      vertices += m.accessors.at(static_cast<std::size_t>(p.attributes.at("POSITION"))).count;
    }
  }
  EXPECT_EQ(vertices, 2u * (4 + 2 + 1));
  EXPECT_EQ(m.meshes.at(1).primitives.size(), 2u);  // infill and wall
  EXPECT_GE(m.materials.size(), 2u);
}

TEST(PreviewGltf, TubesSurroundEachSegmentAtHalfTheBeadWidth) {
  const auto scene = preview_scene(parse_gcode(";WIDTH:0.8\n" + std::string(kThreeLayers)).program, 0.01);
  const auto m = load(render_glb(scene, {.tubes = true, .tube_sides = 6}));
  ASSERT_EQ(m.nodes.size(), 4u);
  const auto& prim = m.meshes.at(0).primitives.at(0);  // layer 0: the 20 mm square, z 0.5
  EXPECT_EQ(prim.mode, TINYGLTF_MODE_TRIANGLES);
  const auto& pos = m.accessors.at(static_cast<std::size_t>(prim.attributes.at("POSITION")));
  EXPECT_EQ(pos.count, 4u * 2 * 6);                                              // 4 segments, 2 rings of 6
  EXPECT_EQ(m.accessors.at(static_cast<std::size_t>(prim.indices)).count, 4u * 6 * 6);  // 2 triangles a side
  EXPECT_NEAR(pos.minValues[0], -0.4, 1e-6);  // the square spans x 0..20, widened by the radius
  EXPECT_NEAR(pos.maxValues[0], 20.4, 1e-6);
  // A hexagon with a vertex sideways: 2 r sin 60 deg tall.
  EXPECT_NEAR(pos.maxValues[2] - pos.minValues[2], 0.8 * std::sqrt(3.0) / 2.0, 1e-6);
}

}  // namespace
}  // namespace strand::post
