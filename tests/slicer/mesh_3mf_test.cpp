// 3MF parts: build items, components, transforms and units, written here as small archives
// (the XML a 3MF package holds, zipped with libzip) so each case states its geometry.
#include "slicer/mesh_3mf.h"

#include <gtest/gtest.h>
#include <zip.h>

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "slicer/input_error.h"
#include "slicer/mesh_io.h"
#include "tests/slicer/mesh_3mf_fixtures.h"
#include "tests/support/cli_runner.h"

namespace strand::slicer {
namespace {

using namespace test3mf;

TEST(Read3mf, CubeInMillimetres) {
  const auto dir = testing::fresh_dir("3mf-cube");
  const Mesh m = read_mesh_file(
      write_3mf(dir, "cube.3mf",
                model("millimeter", "<object id=\"1\" type=\"model\">" + cube_mesh() + "</object>",
                      "<item objectid=\"1\"/>")));
  ASSERT_EQ(m.triangles.size(), 12u);
  EXPECT_NEAR(signed_volume_mm3(m), 1000.0, 1e-6);
  EXPECT_NEAR(bounds(m).max_mm.x(), 10.0, 1e-9);
}

TEST(Read3mf, UnitInchScalesBy25_4) {
  const auto dir = testing::fresh_dir("3mf-inch");
  const Mesh m = read_3mf(
      write_3mf(dir, "inch.3mf",
                model("inch", "<object id=\"1\" type=\"model\">" + cube_mesh(1.0) + "</object>",
                      "<item objectid=\"1\"/>")));
  EXPECT_NEAR(bounds(m).size_mm().x(), 25.4, 1e-5);
  EXPECT_NEAR(signed_volume_mm3(m), 25.4 * 25.4 * 25.4, 1e-2);
}

// A build item with a transform placing a components object whose two components each move
// the same cube: two cubes where the composed transforms put them.
TEST(Read3mf, ComponentsAndTransformsCompose) {
  const auto dir = testing::fresh_dir("3mf-components");
  const std::string resources = "<object id=\"1\" type=\"model\">" + cube_mesh() + "</object>" +
                                "<object id=\"2\" type=\"model\"><components>"
                                "<component objectid=\"1\" transform=\"1 0 0 0 1 0 0 0 1 0 0 0\"/>"
                                "<component objectid=\"1\" transform=\"1 0 0 0 1 0 0 0 1 20 0 0\"/>"
                                "</components></object>";
  // The item turns the pair 90 degrees about z and lifts it by 5 mm.
  const Mesh m =
      read_3mf(write_3mf(dir, "pair.3mf",
                         model("millimeter", resources,
                               "<item objectid=\"2\" transform=\"0 1 0 -1 0 0 0 0 1 0 0 5\"/>")));
  ASSERT_EQ(m.triangles.size(), 24u);
  const Box3 b = bounds(m);
  // x' = -y, y' = x: the cubes span y' in [0, 30] and x' in [-10, 0]; z in [5, 15].
  EXPECT_NEAR(b.min_mm.x(), -10.0, 1e-5);
  EXPECT_NEAR(b.max_mm.x(), 0.0, 1e-5);
  EXPECT_NEAR(b.min_mm.y(), 0.0, 1e-5);
  EXPECT_NEAR(b.max_mm.y(), 30.0, 1e-5);
  EXPECT_NEAR(b.min_mm.z(), 5.0, 1e-5);
  EXPECT_NEAR(signed_volume_mm3(m), 2000.0, 1e-3);
}

// Issue 33: each build item one object, in build order; a components object stays one object
// (its parts placed), and an empty item is named.
TEST(Read3mf, ObjectsAreTheBuildItemsInBuildOrder) {
  const auto dir = testing::fresh_dir("3mf-objects");
  const std::string resources = "<object id=\"1\" type=\"model\">" + cube_mesh() + "</object>" +
                                "<object id=\"2\" type=\"model\"><components>"
                                "<component objectid=\"1\"/>"
                                "<component objectid=\"1\" transform=\"1 0 0 0 1 0 0 0 1 20 0 0\"/>"
                                "</components></object>";
  const std::string path = write_3mf(dir, "items.3mf", model("millimeter", resources,
      "<item objectid=\"2\" transform=\"1 0 0 0 1 0 0 0 1 0 30 0\"/><item objectid=\"1\"/>"));
  const std::vector<Mesh> objects = read_3mf_objects(path);
  ASSERT_EQ(objects.size(), 2u);
  EXPECT_EQ(objects[0].triangles.size(), 24u);
  EXPECT_EQ(objects[0].vertices_mm.size(), 16u);
  EXPECT_NEAR(bounds(objects[0]).min_mm.y(), 30.0, 1e-9);
  EXPECT_NEAR(bounds(objects[0]).max_mm.x(), 30.0, 1e-9);
  EXPECT_EQ(bounds(objects[1]).max_mm, Vec3(10, 10, 10));
  EXPECT_EQ(merge_meshes(objects), read_3mf(path));
  EXPECT_EQ(read_mesh_objects(path), objects);
}

TEST(Read3mf, MirroringTransformKeepsTheOutsideOut) {
  const auto dir = testing::fresh_dir("3mf-mirror");
  const Mesh m = read_3mf(
      write_3mf(dir, "mirror.3mf",
                model("millimeter", "<object id=\"1\" type=\"model\">" + cube_mesh() + "</object>",
                      "<item objectid=\"1\" transform=\"-1 0 0 0 1 0 0 0 1 0 0 0\"/>")));
  EXPECT_NEAR(signed_volume_mm3(m), 1000.0, 1e-6);
  EXPECT_NEAR(bounds(m).min_mm.x(), -10.0, 1e-9);
}

TEST(Read3mf, SliceCommandReadsA3mfPart) {
  const auto dir = testing::fresh_dir("3mf-slice");
  write_3mf(dir, "cube.3mf",
            model("millimeter", "<object id=\"1\" type=\"model\">" + cube_mesh() + "</object>",
                  "<item objectid=\"1\" transform=\"1 0 0 0 1 0 0 0 1 50 50 0\"/>"));
  const auto r = testing::run_strand(
      "slice cube.3mf --pattern scaffold --nozzle 0.6 --gap 1 --perimeters 1 -o cube.gcode", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("part 10.000 x 10.000 x 10.000 mm"), std::string::npos) << r.out;
  const auto c = testing::run_strand("check cube.gcode", dir);
  EXPECT_EQ(c.exit_code, 0) << c.out << c.err;
  const auto units = testing::run_strand(
      "slice cube.3mf --mesh-units in --pattern scaffold --nozzle 0.6 --gap 1 -o inch.gcode", dir);
  EXPECT_EQ(units.exit_code, 2);
  EXPECT_NE(units.err.find("states its own unit"), std::string::npos) << units.err;
}

// ---- Extensions the reader does not know are ignored, as PrusaSlicer does, unless the
// file requires them (issue 29).

// The 3MF Consortium's Materials samples (tests/data/README.md): a 10 cm cube with base
// materials, textures, multiproperties and display properties whose `ms:` elements use a
// prefix no xmlns declares. lib3mf stopped on it ("Could not get XML Namespace").
TEST(Read3mf, ConsortiumMaterialsSamplesReadTheirGeometry) {
  for (const char* name : {"multiprop-metallic.3mf", "multiprop-translucent.3mf"}) {
    const Mesh m = read_mesh_file(std::string(STRAND_SOURCE_DIR) + "/tests/data/" + name);
    EXPECT_EQ(m.triangles.size(), 12u) << name;
    EXPECT_EQ(m.vertices_mm.size(), 8u) << name;
    EXPECT_NEAR(bounds(m).size_mm().x(), 100.0, 1e-6) << name << ": 10 cm";
    EXPECT_NEAR(signed_volume_mm3(m), 1e6, 1e-3) << name << ": outward facing";
  }
}

// A model whose root carries `root_attrs` and whose resources add `extra` after the cube.
std::string extended_model(const std::string& root_attrs, const std::string& extra) {
  return R"(<?xml version="1.0" encoding="UTF-8"?>
<model unit="millimeter" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02" )" +
         root_attrs + "><resources><object id=\"1\" type=\"model\">" + cube_mesh() +
         "</object>" + extra + "</resources><build><item objectid=\"1\"/></build></model>";
}

TEST(Read3mf, UnknownExtensionsAreIgnoredUnlessRequired) {
  const auto dir = testing::fresh_dir("3mf-extensions");
  const std::string q = "xmlns:q=\"http://example.com/3mf/unknown/2024\"";
  const std::string m = "xmlns:m=\"http://schemas.microsoft.com/3dmanufacturing/material/2015/02\"";
  const std::string foreign = "<q:thing q:size=\"3\"><q:part/></q:thing>";
  const std::string undeclared =
      "<zz:displayproperties id=\"5\"><zz:pbr zz:value=\"1\"/></zz:displayproperties>";
  // Declared but unknown, and a prefix nobody declares: both ignored, the cube read.
  for (const auto& [name, xml] : std::vector<std::pair<std::string, std::string>>{
           {"unknown.3mf", extended_model(q, foreign)},
           {"undeclared.3mf", extended_model(m, undeclared)},
           {"materials-required.3mf",
            extended_model(m + " requiredextensions=\"m\"", undeclared)}}) {
    const Mesh mesh = read_mesh_file(write_3mf(dir, name, xml));
    EXPECT_EQ(mesh.triangles.size(), 12u) << name;
  }
  expect_refused(write_3mf(dir, "required.3mf",
                           extended_model(q + " requiredextensions=\"q\"", foreign)),
                 "the file requires the 3MF extension http://example.com/3mf/unknown/2024 "
                 "(requiredextensions 'q'), which Strand does not read");
  expect_refused(write_3mf(dir, "required-undeclared.3mf",
                           extended_model("requiredextensions=\"zz\"", "")),
                 "requires the extension of prefix 'zz', which no xmlns:zz declares");
  // The same through the CLI: exit 2, one line, no output.
  const auto r = testing::run_strand("slice required.3mf --nozzle 0.6 --gap 1 -o out.gcode", dir);
  testing::expect_input_error(r, "requiredextensions 'q'");
  EXPECT_FALSE(testing::exists(dir + "/out.gcode"));
}

TEST(Read3mf, SliceCommandSlicesAConsortiumMaterialsSample) {
  const auto dir = testing::fresh_dir("3mf-multiprop-slice");
  const auto r = testing::run_strand(
      "slice '" + std::string(STRAND_SOURCE_DIR) +
          "/tests/data/multiprop-metallic.3mf' --scale 0.2 --nozzle 0.84 --gap 1.6 -o cube.gcode",
      dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("part 20.000 x 20.000 x 20.000 mm"), std::string::npos) << r.out;
  EXPECT_EQ(testing::run_strand("check cube.gcode --machine deltawasp-2040-clay", dir).exit_code,
            0);
}

}  // namespace
}  // namespace strand::slicer

