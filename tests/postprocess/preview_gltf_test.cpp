// GLB preview: loads back with tinygltf; one node per deposited layer under a root.
#include "postprocess/preview_gltf.h"

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "postprocess/gcode_parser.h"

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

TEST(PreviewGltf, LoadsBackWithARootAndOneNodePerLayer) {
  const auto m = load(render_glb(preview_scene(parse_gcode(kThreeLayers).program, 0.01)));
  ASSERT_EQ(m.nodes.size(), 4u);
  EXPECT_EQ(m.nodes[0].children.size(), 3u);
  ASSERT_EQ(m.scenes.size(), 1u);
  EXPECT_EQ(m.scenes[0].nodes, std::vector<int>{0});
  EXPECT_EQ(m.nodes[0].scale, (std::vector<double>{0.001, 0.001, 0.001}));
}

TEST(PreviewGltf, StrandsAreLinePairsColouredByFeature) {
  const auto m = load(render_glb(preview_scene(parse_gcode(kThreeLayers).program, 0.01)));
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

}  // namespace
}  // namespace strand::post
