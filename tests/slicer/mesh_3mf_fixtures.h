// Small 3MF packages written in the tests (the XML a 3MF package holds, zipped with libzip), so
// each case states its geometry: the content types and relationships parts, a cube's <mesh>, a
// model document and the archive.
#pragma once

#include <zip.h>

#include <cstdlib>
#include <cstring>
#include <string>

#include <gtest/gtest.h>

#include "slicer/input_error.h"
#include "slicer/mesh_io.h"

namespace strand::slicer::test3mf {

inline const char* kContentTypes =
    R"(<?xml version="1.0" encoding="UTF-8"?>
<Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types">
<Default Extension="rels" ContentType="application/vnd.openxmlformats-package.relationships+xml"/>
<Default Extension="model" ContentType="application/vnd.ms-package.3dmanufacturing-3dmodel+xml"/>
</Types>)";
inline const char* kRels =
    R"(<?xml version="1.0" encoding="UTF-8"?>
<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">
<Relationship Target="/3D/3dmodel.model" Id="rel0" Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/>
</Relationships>)";

// A 10 mm cube (unit cube scaled by `size`) as a <mesh> element's content, outward facing.
inline std::string cube_mesh(double size = 10.0) {
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

inline std::string model(const std::string& unit, const std::string& resources, const std::string& build) {
  return R"(<?xml version="1.0" encoding="UTF-8"?>
<model unit=")" +
         unit +
         R"(" xml:lang="en-US" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">
<resources>)" +
         resources + "</resources><build>" + build + "</build></model>";
}

// Writes a 3MF package holding `model_xml` and returns its path.
inline std::string write_3mf(const std::string& dir, const std::string& name,
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

// Reading `path` fails with one line starting "mesh = " and holding `words`.
inline void expect_refused(const std::string& path, const std::string& words) {
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

}  // namespace strand::slicer::test3mf
