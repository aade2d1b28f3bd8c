// 3MF packages refused or bounded: hostile archives, component depth, loops and fan-out,
// resource counts, XML nesting, stated sizes, and components in another model part (issue 29).
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

}  // namespace
}  // namespace strand::slicer
