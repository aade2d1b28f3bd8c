// Mesh files: every format reads to the same triangles, units and placement apply, bad
// files fail with one InputError naming the file.
#include "slicer/mesh_io.h"

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "slicer/file_io.h"
#include "slicer/input_error.h"
#include "slicer/units.h"
#include "tests/support/cli_runner.h"
#include "tests/support/mesh_shapes.h"

namespace strand::slicer {
namespace {

using testing::box_mesh;

// ASCII PLY, written here (the reader's only PLY user).
void write_ply(const Mesh& m, const std::string& path) {
  std::string out =
      "ply\nformat ascii 1.0\nelement vertex " + std::to_string(m.vertices_mm.size()) +
      "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
      std::to_string(m.triangles.size()) + "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const Vec3& v : m.vertices_mm) {
    out += std::to_string(v.x()) + " " + std::to_string(v.y()) + " " + std::to_string(v.z()) + "\n";
  }
  for (const auto& t : m.triangles) {
    out += "3 " + std::to_string(t[0]) + " " + std::to_string(t[1]) + " " + std::to_string(t[2]) +
           "\n";
  }
  write_file_atomic(path, out);
}

TEST(MeshIo, EveryOpenMeshFormatReadsTheSameBox) {
  const auto dir = testing::fresh_dir("mesh-io");
  const Mesh box = box_mesh(Vec3(10, 20, 30));
  testing::write_binary_stl(box, dir + "/b.stl");
  testing::write_ascii_stl(box, dir + "/a.stl");
  testing::write_obj(box, dir + "/o.obj");
  testing::write_off(box, dir + "/f.off");
  testing::write_binary_stl(box, dir + "/UPPER.STL");
  write_ply(box, dir + "/p.ply");
  for (const char* name : {"b.stl", "a.stl", "o.obj", "f.off", "UPPER.STL", "p.ply"}) {
    const Mesh m = read_mesh_file(dir + "/" + name);
    EXPECT_EQ(m.triangles.size(), 12u) << name;
    EXPECT_EQ(m.vertices_mm.size(), 8u) << name << ": STL corners are merged";
    EXPECT_NEAR(signed_volume_mm3(m), 6000.0, 1e-6) << name;
  }
}

TEST(MeshIo, ObjTextureCoordinatesAreKept) {
  const auto dir = testing::fresh_dir("mesh-uv");
  const Mesh plate = testing::plate_mesh(20, 10, 1, 4, 2);
  testing::write_obj(plate, dir + "/p.obj");
  const Mesh m = read_mesh_file(dir + "/p.obj");
  ASSERT_EQ(m.uv.size(), m.vertices_mm.size());
  for (std::size_t i = 0; i < m.uv.size(); ++i) {
    EXPECT_NEAR(m.uv[i].x(), m.vertices_mm[i].x(), 1e-6);
    EXPECT_NEAR(m.uv[i].y(), m.vertices_mm[i].y(), 1e-6);
  }
}

// A one-triangle-pair glTF written with tinygltf: +Y up in the file becomes +Z up.
TEST(MeshIo, GlbIsReadWithYUpTurnedToZUp) {
  const auto dir = testing::fresh_dir("mesh-glb");
  tinygltf::Model g;
  const float pos[] = {0, 0, 0, 1, 0, 0, 0, 5, 0};  // a triangle standing 5 up in +Y
  tinygltf::Buffer buf;
  buf.data.resize(sizeof pos);
  std::memcpy(buf.data.data(), pos, sizeof pos);
  g.buffers.push_back(buf);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteLength = sizeof pos;
  g.bufferViews.push_back(view);
  tinygltf::Accessor acc;
  acc.bufferView = 0;
  acc.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  acc.type = TINYGLTF_TYPE_VEC3;
  acc.count = 3;
  acc.minValues = {0, 0, 0};
  acc.maxValues = {1, 5, 0};
  g.accessors.push_back(acc);
  tinygltf::Primitive prim;
  prim.attributes["POSITION"] = 0;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  tinygltf::Mesh mesh;
  mesh.primitives.push_back(prim);
  g.meshes.push_back(mesh);
  tinygltf::Node node;
  node.mesh = 0;
  node.translation = {10, 0, 0};
  g.nodes.push_back(node);
  g.scenes.push_back(tinygltf::Scene{});
  g.scenes[0].nodes = {0};
  g.defaultScene = 0;
  tinygltf::TinyGLTF writer;
  ASSERT_TRUE(writer.WriteGltfSceneToFile(&g, dir + "/t.glb", true, true, false, true));
  const Mesh m = read_mesh_file(dir + "/t.glb");
  ASSERT_EQ(m.triangles.size(), 1u);
  const Box3 b = bounds(m);
  EXPECT_NEAR(b.min_mm.x(), 10.0, 1e-6);
  EXPECT_NEAR(b.max_mm.z(), 5.0, 1e-6) << "glTF's +Y is Strand's +Z";
}

TEST(MeshIo, UnitsRotationAndPlacement) {
  Mesh box = box_mesh(Vec3(1, 2, 3));
  for (Vec3& v : box.vertices_mm) v += Vec3(5, 5, 5);
  const Mesh cm = place_mesh(box, {kMmPerCm, Vec3::Zero(), Placement::Center});
  const Box3 b = bounds(cm);
  EXPECT_TRUE(b.min_mm.isApprox(Vec3(-5, -10, 0)));
  EXPECT_TRUE(b.max_mm.isApprox(Vec3(5, 10, 30)));
  const Mesh turned = place_mesh(box, {1.0, Vec3(90, 0, 0), Placement::Center});
  EXPECT_NEAR(bounds(turned).size_mm().z(), 2.0, 1e-9) << "y became z";
  const Mesh origin = place_mesh(box, {1.0, Vec3::Zero(), Placement::Origin});
  EXPECT_NEAR(bounds(origin).min_mm.x(), 5.0, 1e-12) << "x/y kept";
  EXPECT_NEAR(bounds(origin).min_mm.z(), 0.0, 1e-12) << "always on the bed";
  EXPECT_EQ(mm_per_mesh_unit("u", "in"), 25.4);
  EXPECT_THROW(mm_per_mesh_unit("u", "ft"), InputError);
}

std::string error_of(const std::string& path) {
  try {
    read_mesh_file(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(MeshIo, BadFilesFailWithOneLineNamingTheFile) {
  const auto dir = testing::fresh_dir("mesh-bad");
  write_file_atomic(dir + "/empty.stl", "");
  write_file_atomic(dir + "/junk.stl", "this is not a mesh at all\n");
  write_file_atomic(dir + "/x.amf", "PK");
  Mesh nan_box = box_mesh(Vec3(1, 1, 1));
  nan_box.vertices_mm[3].y() = std::nan("");
  testing::write_binary_stl(nan_box, dir + "/nan.stl");
  write_file_atomic(dir + "/bad.gltf", "{ not json");
  EXPECT_NE(error_of(dir + "/missing.stl").find("no such file"), std::string::npos);
  EXPECT_NE(error_of(dir + "/empty.stl").find("empty"), std::string::npos);
  EXPECT_FALSE(error_of(dir + "/junk.stl").empty());
  EXPECT_NE(error_of(dir + "/x.amf").find("unknown format"), std::string::npos);
  EXPECT_NE(error_of(dir + "/bad.gltf").find("glTF"), std::string::npos);
  const std::string nan = error_of(dir + "/nan.stl");
  EXPECT_NE(nan.find("has a non-finite coordinate"), std::string::npos) << nan;
  for (const char* f : {"missing.stl", "empty.stl", "junk.stl", "x.amf", "nan.stl", "bad.gltf"}) {
    EXPECT_EQ(error_of(dir + "/" + f).find('\n'), std::string::npos) << f;
  }
}

// OpenMesh's PLY reader sizes its tables from the header: a header with binary bytes in a
// property line (found by mesh_fuzz; OpenMesh allocated 2.4 GB) or counts the file cannot
// hold is refused before it reads anything.
TEST(MeshIo, PlyHeadersAreCheckedBeforeOpenMeshReadsThem) {
  const auto dir = testing::fresh_dir("mesh-ply");
  std::string binary_junk = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\np";
  binary_junk += std::string("\x01\0\0\0rty float y\n", 16);
  binary_junk += "end_header\n0 0 0\n";
  write_file_atomic(dir + "/junk.ply", binary_junk);
  write_file_atomic(dir + "/huge.ply",
                    "ply\nformat ascii 1.0\nelement vertex 99999999999\nproperty float x\n"
                    "property float y\nproperty float z\nend_header\n0 0 0\n");
  write_file_atomic(dir + "/nohead.ply", "ply\nformat ascii 1.0\nelement vertex 3\n");
  write_file_atomic(dir + "/type.ply",
                    "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar quad v\n"
                    "end_header\n3 0 1 2\n");
  EXPECT_NE(error_of(dir + "/junk.ply").find("PLY header line 5: holds a byte that is not text"),
            std::string::npos)
      << error_of(dir + "/junk.ply");
  EXPECT_NE(error_of(dir + "/huge.ply").find("PLY header line 3: an element count must be 0 .."),
            std::string::npos);
  EXPECT_NE(error_of(dir + "/nohead.ply").find("no end_header line"), std::string::npos);
  write_file_atomic(
      dir + "/glued.ply",  // OpenMesh looped without end on it (mesh_fuzz)
      "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_headernt v 0\n");
  EXPECT_NE(error_of(dir + "/glued.ply").find("no end_header line"), std::string::npos);
  write_file_atomic(dir + "/format.ply",  // OpenMesh looped without end on it (mesh_fuzz)
                    "ply\nformat ascii uchaq hnt vertex_indices\nend_header\n0 0 0\n");
  EXPECT_NE(error_of(dir + "/format.ply").find("line 2: the format version must be 1.0"),
            std::string::npos)
      << error_of(dir + "/format.ply");
  EXPECT_NE(error_of(dir + "/type.ply").find("a property type must be one of"), std::string::npos);
  write_file_atomic(dir + "/orphan.ply",  // OpenMesh crashed on it (mesh_fuzz)
                    "ply\nformat ascii 1.0\nproperty float z\nelement face 1\n"
                    "property list uchar int vertex_indices\nend_header\n3 0 1 2\n");
  EXPECT_NE(error_of(dir + "/orphan.ply").find("line 3: a property before any element line"),
            std::string::npos)
      << error_of(dir + "/orphan.ply");
}

// NaN and infinite vertices are named as such (readers merged or dropped them and the check
// said "no triangles" or "open mesh").
TEST(MeshIo, NonFiniteVerticesAreNamedInEveryTextFormat) {
  const auto dir = testing::fresh_dir("mesh-nan");
  write_file_atomic(dir + "/a.stl",
                    "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 nan 0\n"
                    "vertex 0 1 0\nendloop\nendfacet\nendsolid t\n");
  write_file_atomic(dir + "/a.obj", "v 0 0 0\nv 1 0 0\nv 0 inf 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\n");
  write_file_atomic(dir + "/a.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n0 -inf 0\n0 0 1\n3 0 1 2\n");
  Mesh box = box_mesh(Vec3(1, 1, 1));
  write_ply(box, dir + "/a.ply");
  std::string ply = testing::slurp(dir + "/a.ply");
  const std::size_t body = ply.find("end_header\n") + 11;
  std::string word = ply;
  ply.replace(body, ply.find(' ', body) - body, "nan");
  write_file_atomic(dir + "/a.ply", ply);
  // A word in the body: OpenMesh spun for two minutes on it (also a mesh_fuzz regression).
  word.replace(body, word.find(' ', body) - body, "nan.000000");
  write_file_atomic(dir + "/word.ply", word);
  EXPECT_NE(error_of(dir + "/word.ply").find("PLY line 10: 'nan.000000' is not a number"),
            std::string::npos)
      << error_of(dir + "/word.ply");
  for (const auto& [file, where] : std::vector<std::pair<std::string, std::string>>{
           {"a.stl", "line 5 has a non-finite coordinate ('nan'"},
           {"a.obj", "line 3 has a non-finite coordinate ('inf'"},
           {"a.off", "line 5 has a non-finite coordinate ('-inf'"},
           {"a.ply", "line 10 has a non-finite coordinate ('nan'"}}) {
    const std::string e = error_of(dir + "/" + file);
    EXPECT_NE(e.find(where), std::string::npos) << file << ": " << e;
  }
}

std::string tetra_gltf() {
  // The mesh_fuzz seed: a tetrahedron with its buffer inline (the first byte picks the format).
  return testing::slurp(std::string(STRAND_SOURCE_DIR) + "/tests/fuzz/seeds/mesh_fuzz/tetra.gltf")
      .substr(1);
}

// glTF accessors, views and buffers are checked against each other before any byte is read
// (a bufferView out of range segfaulted; counts times strides overflowed); each case is also
// a mesh_fuzz regression input.
TEST(MeshIo, GltfStructureIsBoundedBeforeReading) {
  const auto dir = testing::fresh_dir("mesh-gltf-bounds");
  const std::string regressions =
      std::string(STRAND_SOURCE_DIR) + "/tests/fuzz/regressions/mesh_fuzz/";
  for (const auto& [file, says] : std::vector<std::pair<std::string, std::string>>{
           {"gltf-bufferview-out-of-range.gltf", "POSITION accessor is not float VEC3 data inside"},
           {"gltf-view-buffer-out-of-range.gltf", "mesh = "},
           {"gltf-accessor-count-overflow.gltf", "mesh = "},
           {"gltf-view-past-buffer.gltf", "mesh = "}}) {
    write_file_atomic(dir + "/" + file, testing::slurp(regressions + file).substr(1));
    const std::string e = error_of(dir + "/" + file);
    EXPECT_NE(e.find(says), std::string::npos) << file << ": " << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << file;
  }
  // Nodes listing the next one twice, 63 deep: 2^63 paths, each node visited once.
  write_file_atomic(dir + "/fan.gltf",
                    testing::slurp(regressions + "gltf-node-fan-out.gltf").substr(1));
  EXPECT_EQ(read_mesh_file(dir + "/fan.gltf").triangles.size(), 4u);
  // A chain deeper than 64 nodes is refused.
  nlohmann::json deep = nlohmann::json::parse(tetra_gltf());
  deep["nodes"] = nlohmann::json::array();
  for (int i = 0; i < 80; ++i) deep["nodes"].push_back({{"children", {i + 1}}});
  deep["nodes"].push_back({{"mesh", 0}});
  write_file_atomic(dir + "/deep.gltf", deep.dump());
  EXPECT_NE(error_of(dir + "/deep.gltf").find("the node tree is deeper than 64 levels"),
            std::string::npos)
      << error_of(dir + "/deep.gltf");
}

TEST(MeshIo, GltfBuffersNamedByUriCountAgainstTheInputLimit) {
  const auto dir = testing::fresh_dir("mesh-gltf-uri");
  nlohmann::json g = nlohmann::json::parse(tetra_gltf());
  g["buffers"][0]["uri"] = "big.bin";
  write_file_atomic(dir + "/big.gltf", g.dump());
  // A sparse 300 MiB file: refused by its size, never read.
  std::filesystem::resize_file(
      [&] {
        write_file_atomic(dir + "/big.bin", "x");
        return dir + "/big.bin";
      }(),
      std::uintmax_t{300} << 20);
  const std::string e = error_of(dir + "/big.gltf");
  EXPECT_NE(e.find("mesh = " + dir +
                   "/big.gltf: 'big.bin' would take the mesh and the files it "
                   "names past the 256 MiB input limit"),
            std::string::npos)
      << e;
  // An embedded image that is not an image at all is never decoded: the mesh reads.
  nlohmann::json with_image = nlohmann::json::parse(tetra_gltf());
  with_image["images"] = {{{"uri", "data:image/png;base64,AAAAAAAA"}}};
  write_file_atomic(dir + "/image.gltf", with_image.dump());
  EXPECT_EQ(read_mesh_file(dir + "/image.gltf").triangles.size(), 4u);
}

// Every count of a mesh file is bounded by the bytes that follow it and by the documented
// limits before a reader allocates for it (issue 29: a 331-byte binary PLY whose one face
// list claims 2^31 - 1 indices took 8.4 GB and 60 s). The reproducer is
// tests/data/ply-list-count-2e31.ply; the others are written here.
TEST(MeshIo, ListAndFaceCountsAreBoundedBeforeAnyAllocation) {
  const auto dir = testing::fresh_dir("mesh-counts");
  const std::string hostile =
      std::string(STRAND_SOURCE_DIR) + "/tests/data/ply-list-count-2e31.ply";
  const auto start = std::chrono::steady_clock::now();
  const std::string binary = error_of(hostile);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
  EXPECT_NE(binary.find("PLY face 0: a list of 2147483647 entries needs 8589934588 bytes; 12 are "
                        "left in the file"),
            std::string::npos)
      << binary;
  const std::string tri =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uint int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n";
  write_file_atomic(dir + "/ascii.ply", tri + "2147483647 0 1 2\n");
  EXPECT_NE(error_of(dir + "/ascii.ply").find("PLY face 0: a list of 2147483647 entries; only"),
            std::string::npos)
      << error_of(dir + "/ascii.ply");
  // A face's flags byte after its list is missing: the file ends inside the record.
  std::string cut =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uchar int vertex_indices\nproperty uchar flags\nend_header\n";
  cut += std::string(36, '\0') + "\x03" + std::string(12, '\0');
  write_file_atomic(dir + "/short.ply", cut);
  EXPECT_NE(error_of(dir + "/short.ply").find("PLY face 0: the file ends before this record does"),
            std::string::npos)
      << error_of(dir + "/short.ply");
  write_file_atomic(dir + "/float-count.ply",
                    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nelement face 1\n"
                    "property list float int vertex_indices\nend_header\n0\n0\n0\n3 0 1 2\n");
  EXPECT_NE(error_of(dir + "/float-count.ply").find("a list count type must be an integer type"),
            std::string::npos);
  // Records at their smallest (12 bytes a binary vertex) must fit after the header.
  write_file_atomic(dir + "/records.ply",
                    "ply\nformat binary_little_endian 1.0\nelement vertex 20\nproperty float x\n"
                    "property float y\nproperty float z\nelement face 0\n"
                    "property list uchar int vertex_indices\nend_header\n" +
                        std::string(200, '\0'));
  EXPECT_NE(error_of(dir + "/records.ply")
                .find("PLY element vertex 20: records of at least 12 bytes each; the file has "
                      "200 bytes after its header"),
            std::string::npos)
      << error_of(dir + "/records.ply");
  const std::string off = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n";
  write_file_atomic(dir + "/face.off", off + "2147483647 0 1 2\n");
  write_file_atomic(dir + "/negative.off", off + "-5 0 1 2\n");
  EXPECT_NE(error_of(dir + "/face.off")
                .find("OFF line 6: face 0's corner count must be a whole "
                      "number 0 .. 4000002 (it is '2147483647')"),
            std::string::npos)
      << error_of(dir + "/face.off");
  EXPECT_NE(error_of(dir + "/negative.off").find("OFF line 6: face 0's corner count"),
            std::string::npos)
      << error_of(dir + "/negative.off");
  write_file_atomic(dir + "/ok.off", off + "3 0 1 2 255 0 0\n");  // a colour after the face
  EXPECT_EQ(read_mesh_file(dir + "/ok.off").triangles.size(), 1u);
  // One OBJ face of n corners becomes n - 2 triangles: more than the limit is refused.
  std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf";
  obj.reserve(obj.size() + 2 * (kMaxMeshTriangles + 3));
  for (std::size_t k = 0; k < kMaxMeshTriangles + 3; ++k) obj += " 1";
  write_file_atomic(dir + "/fan.obj", obj + "\n");
  EXPECT_NE(error_of(dir + "/fan.obj")
                .find("OBJ line 4: the faces make more than 4000000 "
                      "triangles"),
            std::string::npos)
      << error_of(dir + "/fan.obj");
  for (const char* f :
       {"ascii.ply", "short.ply", "records.ply", "face.off", "negative.off", "fan.obj"}) {
    EXPECT_EQ(error_of(dir + "/" + f).find('\n'), std::string::npos) << f;
  }
}

// The same through the CLI under a 300 MB address-space limit (the old reader asked for
// 8 GB): exit 2, one line naming the list, in well under a second.
TEST(MeshIo, HostilePlyExitsTwoInOneLineWithinLimits) {
#ifdef STRAND_SANITIZE_BUILD
  GTEST_SKIP() << "AddressSanitizer reserves more address space than the limit";
#endif
  const auto dir = testing::fresh_dir("mesh-counts-cli");
  const std::string hostile =
      std::string(STRAND_SOURCE_DIR) + "/tests/data/ply-list-count-2e31.ply";
  const auto start = std::chrono::steady_clock::now();
  const auto r = testing::run_in_shell(
      "ulimit -v 300000; '" + std::string(STRAND_CLI) + "' mesh '" + hostile + "'", dir);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
  testing::expect_input_error(r, "a list of 2147483647 entries needs 8589934588 bytes");
}

}  // namespace
}  // namespace strand::slicer
