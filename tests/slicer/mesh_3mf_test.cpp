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
#include "tests/support/cli_runner.h"

namespace strand::slicer {
namespace {

const char* kContentTypes =
    R"(<?xml version="1.0" encoding="UTF-8"?>
<Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types">
<Default Extension="rels" ContentType="application/vnd.openxmlformats-package.relationships+xml"/>
<Default Extension="model" ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/>
</Types>)";
const char* kRels =
    R"(<?xml version="1.0" encoding="UTF-8"?>
<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">
<Relationship Target="/3D/3dmodel.model" Id="rel0" Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/>
</Relationships>)";

// A 10 mm cube (unit cube scaled by `size`) as a <mesh> element's content, outward facing.
std::string cube_mesh(double size = 10.0) {
  std::string v;
  for (int i = 0; i < 8; ++i) {
    v += "<vertex x=\"" + std::to_string((i & 1) * size) + "\" y=\"" +
         std::to_string(((i >> 1) & 1) * size) + "\" z=\"" + std::to_string(((i >> 2) & 1) * size) +
         "\"/>";
  }
  const int t[12][3] = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                        {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  std::string f;
  for (const auto& tri : t) {
    f += "<triangle v1=\"" + std::to_string(tri[0]) + "\" v2=\"" + std::to_string(tri[1]) +
         "\" v3=\"" + std::to_string(tri[2]) + "\"/>";
  }
  return "<mesh><vertices>" + v + "</vertices><triangles>" + f + "</triangles></mesh>";
}

std::string model(const std::string& unit, const std::string& resources, const std::string& build) {
  return R"(<?xml version="1.0" encoding="UTF-8"?>
<model unit=")" +
         unit +
         R"(" xml:lang="en-US" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">
<resources>)" +
         resources + "</resources><build>" + build + "</build></model>";
}

// Writes a 3MF package holding `model_xml` and returns its path.
std::string write_3mf(const std::string& dir, const std::string& name,
                      const std::string& model_xml) {
  const std::string path = dir + "/" + name;
  int error = 0;
  zip_t* z = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &error);
  EXPECT_NE(z, nullptr);
  const auto add = [&](const char* entry, const std::string& text) {
    char* copy = static_cast<char*>(malloc(text.size()));
    std::memcpy(copy, text.data(), text.size());
    zip_source_t* s = zip_source_buffer(z, copy, text.size(), 1);
    EXPECT_GE(zip_file_add(z, entry, s, ZIP_FL_OVERWRITE), 0);
  };
  add("[Content_Types].xml", kContentTypes);
  add("_rels/.rels", kRels);
  add("3D/3dmodel.model", model_xml);
  EXPECT_EQ(zip_close(z), 0);
  return path;
}

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

void expect_refused(const std::string& path, const std::string& words) {
  try {
    read_mesh_file(path);
    ADD_FAILURE() << "no error for " << path;
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(words), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    EXPECT_EQ(what.rfind("mesh = ", 0), 0u) << what;
  }
}

TEST(Read3mf, HostileFilesAreRefusedInOneLine) {
  const auto dir = testing::fresh_dir("3mf-hostile");
  {
    const std::string path = dir + "/text.3mf";
    std::ofstream(path) << "solid not a zip\n";
    expect_refused(path, "not a 3MF file");
  }
  // A zip without a model part.
  {
    const std::string path = dir + "/empty.3mf";
    int error = 0;
    zip_t* z = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &error);
    zip_source_t* s = zip_source_buffer(z, "x", 1, 0);
    zip_file_add(z, "readme.txt", s, 0);
    zip_close(z);
    expect_refused(path, "3MF");
  }
  // A triangle naming a vertex that is not there.
  expect_refused(
      write_3mf(dir, "index.3mf",
                model("millimeter",
                      "<object id=\"1\" type=\"model\"><mesh><vertices>"
                      "<vertex x=\"0\" y=\"0\" z=\"0\"/><vertex x=\"1\" y=\"0\" z=\"0\"/>"
                      "<vertex x=\"0\" y=\"1\" z=\"0\"/></vertices><triangles>"
                      "<triangle v1=\"0\" v2=\"1\" v3=\"7\"/></triangles></mesh></object>",
                      "<item objectid=\"1\"/>")),
      "3MF");
  // Components that fan out: 40 levels of two copies each (2^40 cubes) are counted, not built.
  {
    std::string resources = "<object id=\"1\" type=\"model\">" + cube_mesh() + "</object>";
    for (int id = 2; id <= 41; ++id) {
      const std::string child = std::to_string(id - 1);
      resources += "<object id=\"" + std::to_string(id) + "\" type=\"model\"><components>" +
                   "<component objectid=\"" + child + "\"/><component objectid=\"" + child +
                   "\"/></components></object>";
    }
    expect_refused(
        write_3mf(dir, "fan.3mf", model("millimeter", resources, "<item objectid=\"41\"/>")),
        "objects, each nested component copy counted");
  }
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

// ---- Packages refused before lib3mf reads them: lib3mf 1.8.1 itself walks every build
// item's whole component tree while reading (2^40 copies: hours) and looks resources up by
// linear search, so these bounds hold on the archive's own text.

// A package of the given parts (name, text); `store` writes them uncompressed.
std::string write_parts(const std::string& dir, const std::string& name,
                        const std::vector<std::pair<std::string, std::string>>& parts,
                        bool store = false) {
  const std::string path = dir + "/" + name;
  int error = 0;
  zip_t* z = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &error);
  EXPECT_NE(z, nullptr);
  for (const auto& [entry, text] : parts) {
    char* copy = static_cast<char*>(malloc(text.size()));
    std::memcpy(copy, text.data(), text.size());
    zip_source_t* s = zip_source_buffer(z, copy, text.size(), 1);
    const zip_int64_t index = zip_file_add(z, entry.c_str(), s, ZIP_FL_OVERWRITE);
    EXPECT_GE(index, 0);
    if (store) zip_set_file_compression(z, static_cast<zip_uint64_t>(index), ZIP_CM_STORE, 0);
  }
  EXPECT_EQ(zip_close(z), 0);
  return path;
}

// Objects 2..levels+1 each hold the one below as a component; the build places the top one.
std::string chain_model(int levels) {
  std::string resources = "<object id=\"1\" type=\"model\">" + cube_mesh() + "</object>";
  for (int id = 2; id <= levels + 1; ++id) {
    resources += "<object id=\"" + std::to_string(id) +
                 "\" type=\"model\"><components><component objectid=\"" + std::to_string(id - 1) +
                 "\"/></components></object>";
  }
  return model("millimeter", resources, "<item objectid=\"" + std::to_string(levels + 1) + "\"/>");
}

TEST(Read3mf, SixtyFourComponentLevelsAreReadSixtyFiveRefused) {
  const auto dir = testing::fresh_dir("3mf-depth");
  const Mesh m = read_3mf(write_3mf(dir, "deep64.3mf", chain_model(64)));
  EXPECT_EQ(m.triangles.size(), 12u);
  EXPECT_NEAR(signed_volume_mm3(m), 1000.0, 1e-6);
  expect_refused(write_3mf(dir, "deep65.3mf", chain_model(65)),
                 "components nest deeper than 64 levels");
  // A chain far past the bound (lib3mf would recurse once per level) is refused the same way.
  expect_refused(write_3mf(dir, "deep3000.3mf", chain_model(3000)),
                 "components nest deeper than 64 levels");
}

TEST(Read3mf, ComponentLoopsAreRefused) {
  const auto dir = testing::fresh_dir("3mf-loop");
  const std::string pair =
      "<object id=\"1\" type=\"model\">" + cube_mesh() + "</object>" +
      "<object id=\"2\" type=\"model\"><components><component objectid=\"3\"/></components>"
      "</object><object id=\"3\" type=\"model\"><components><component objectid=\"2\"/>"
      "<component objectid=\"1\"/></components></object>";
  expect_refused(write_3mf(dir, "loop.3mf", model("millimeter", pair, "<item objectid=\"2\"/>")),
                 "components refer to each other in a loop");
  const std::string self =
      "<object id=\"2\" type=\"model\"><components><component "
      "objectid=\"2\"/></components></object>";
  expect_refused(write_3mf(dir, "self.3mf", model("millimeter", self, "<item objectid=\"2\"/>")),
                 "in a loop");
}

// 20 levels of three copies each: 3^20 (3.5e9) cubes, refused from the text in moments.
TEST(Read3mf, FanOutIsCountedNotExpanded) {
  const auto dir = testing::fresh_dir("3mf-fan3");
  std::string resources = "<object id=\"1\" type=\"model\">" + cube_mesh() + "</object>";
  for (int id = 2; id <= 21; ++id) {
    const std::string c = "<component objectid=\"" + std::to_string(id - 1) + "\"/>";
    resources += "<object id=\"" + std::to_string(id) + "\" type=\"model\"><components>" + c + c +
                 c + "</components></object>";
  }
  const auto start = std::chrono::steady_clock::now();
  expect_refused(
      write_3mf(dir, "fan3.3mf", model("millimeter", resources, "<item objectid=\"21\"/>")),
      "its build items place 5230176601 objects, each nested component copy counted; at most "
      "1000000 are accepted");
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10));
}

TEST(Read3mf, TooManyResourcesAreRefusedBeforeLib3mf) {
  const auto dir = testing::fresh_dir("3mf-many");
  std::string resources;
  for (int id = 1; id <= 10001; ++id) {
    resources += "<object id=\"" + std::to_string(id) +
                 "\" type=\"model\"><mesh><vertices/><triangles/></mesh></object>";
  }
  expect_refused(
      write_3mf(dir, "many.3mf", model("millimeter", resources, "<item objectid=\"1\"/>")),
      "more than 10000 resources, components and build items");
}

TEST(Read3mf, DeepXmlNestingIsRefused) {
  const auto dir = testing::fresh_dir("3mf-xml-depth");
  std::string nested;
  for (int i = 0; i < 70; ++i) nested = "<x>" + nested + "</x>";
  const std::string resources =
      "<object id=\"1\" type=\"model\">" + cube_mesh() + "</object>" + nested;
  expect_refused(
      write_3mf(dir, "xml.3mf", model("millimeter", resources, "<item objectid=\"1\"/>")),
      "nests its XML elements deeper than 64 levels");
}

// The archive's directory states each part's inflated size: a lie either way is refused.
TEST(Read3mf, StatedSizesAreBoundAndChecked) {
  const auto dir = testing::fresh_dir("3mf-sizes");
  const std::string cube =
      model("millimeter", "<object id=\"1\" type=\"model\">" + cube_mesh() + "</object>",
            "<item objectid=\"1\"/>");
  const auto parts = std::vector<std::pair<std::string, std::string>>{
      {"[Content_Types].xml", kContentTypes}, {"_rels/.rels", kRels}, {"3D/3dmodel.model", cube}};
  const std::string stored = write_parts(dir, "stored.3mf", parts, true);
  ASSERT_EQ(read_3mf(stored).triangles.size(), 12u);
  // The uncompressed size of the model in the central directory (offset 24 of its entry).
  const auto with_stated_size = [&](const std::string& name, std::uint32_t size) {
    std::string bytes = testing::slurp(stored);
    const std::string entry = std::string("PK\x01\x02", 4);
    std::size_t at = bytes.find(entry);
    while (at != std::string::npos &&
           bytes.compare(at + 46, std::strlen("3D/3dmodel.model"), "3D/3dmodel.model") != 0) {
      at = bytes.find(entry, at + 1);
    }
    EXPECT_NE(at, std::string::npos);
    for (int k = 0; k < 4; ++k)
      bytes[at + 24 + static_cast<std::size_t>(k)] = static_cast<char>((size >> (8 * k)) & 0xff);
    std::ofstream(dir + "/" + name, std::ios::binary) << bytes;
    return dir + "/" + name;
  };
  expect_refused(with_stated_size("huge.3mf", 0xfffff000u),
                 "the archive inflates to 4095 MiB, more than the 512 MiB limit");
  expect_refused(with_stated_size("short.3mf", 100), "3dmodel.model");
}

// Production extension: the root model places an object of another model part; both parts
// number their objects from 1 (the root's object 1 is not its own component).
TEST(Read3mf, ComponentsInAnotherModelPartAreFound) {
  const auto dir = testing::fresh_dir("3mf-parts");
  const std::string p = "http://schemas.microsoft.com/3dmanufacturing/production/2015/06";
  const std::string core = "http://schemas.microsoft.com/3dmanufacturing/core/2015/02";
  const std::string part =
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?><model unit=\"millimeter\" "
      "xmlns=\"" +
      core + "\" xmlns:p=\"" + p +
      "\"><resources><object id=\"1\" type=\"model\" "
      "p:UUID=\"11111111-1111-1111-1111-111111111111\">" +
      cube_mesh() + "</object></resources><build/></model>";
  const std::string root =
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?><model unit=\"millimeter\" xmlns=\"" + core +
      "\" xmlns:p=\"" + p +
      "\" requiredextensions=\"p\"><resources><object id=\"1\" type=\"model\" "
      "p:UUID=\"22222222-1111-1111-1111-111111111111\"><components>"
      "<component objectid=\"1\" p:path=\"/3D/Objects/part.model\" "
      "p:UUID=\"33333333-1111-1111-1111-111111111111\"/>"
      "<component objectid=\"1\" p:path=\"/3D/Objects/part.model\" "
      "p:UUID=\"44444444-1111-1111-1111-111111111111\" transform=\"1 0 0 0 1 0 0 0 1 20 0 0\"/>"
      "</components></object></resources><build p:UUID=\"55555555-1111-1111-1111-111111111111\">"
      "<item objectid=\"1\" p:UUID=\"66666666-1111-1111-1111-111111111111\"/></build></model>";
  const std::string model_rels =
      R"(<?xml version="1.0" encoding="UTF-8"?><Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships"><Relationship Target="/3D/Objects/part.model" Id="rel1" Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/></Relationships>)";
  const Mesh m = read_3mf(write_parts(dir, "parts.3mf",
                                      {{"[Content_Types].xml", kContentTypes},
                                       {"_rels/.rels", kRels},
                                       {"3D/_rels/3dmodel.model.rels", model_rels},
                                       {"3D/Objects/part.model", part},
                                       {"3D/3dmodel.model", root}}));
  ASSERT_EQ(m.triangles.size(), 24u);
  EXPECT_NEAR(bounds(m).max_mm.x(), 30.0, 1e-5);
  EXPECT_NEAR(signed_volume_mm3(m), 2000.0, 1e-3);
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
