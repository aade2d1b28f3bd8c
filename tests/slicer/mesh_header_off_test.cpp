// OFF files walked in OpenMesh's own reading order before it reads them
// (slicer/mesh_header_off.cpp): refused where its stream would stop or misread, read where not.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "slicer/file_io.h"
#include "slicer/input_error.h"
#include "slicer/mesh_io.h"
#include "tests/support/cli_runner.h"

namespace strand::slicer {
namespace {

// OpenMesh's OFF reader takes every number with `>>`; where one does not parse, each later
// read keeps its old value and the face loop reran a stale corner count for every face left
// (found by mesh_fuzz). Files are walked in its own order first and refused where it would go
// wrong, naming the line and the word.
TEST(MeshHeaderOff, FilesAreWalkedInOpenMeshsOrderBeforeItReadsThem) {
  const auto dir = testing::fresh_dir("mesh-off");
  const std::string tri = "0 0 0\n1 0 0\n0 1 0\n";
  struct Refused {
    std::string name, text, message;  // the file, and a part of the one-line error it gets
  };
  const std::vector<Refused> cases = {
      {"garbled.off", "OFF\n400=aM--M--M je 43\n0 0 0\n",
       "OFF line 2: the vertex count must be a whole number 0 .. 12000000 (it is "
       "'400=aM--M--M')"},
      {"huge.off", "OFF\n9e9 1 0\n0 0 0\n", "the vertex count must be a whole number"},
      {"binary.off", "OFF BINARY\n", "binary files are not read"},
      {"dimension.off", "4OFF\n3 1 0\n" + tri + "3 0 1 2\n",
       "header '4OFF': OpenMesh reads OFF, COFF, NOFF, STOFF"},
      // OpenMesh skips the rest of the OFF line: counts there were never read (mesh_fuzz, CI:
      // a 2 GB reservation for "OFF 3 0 1").
      {"inline.off", "OFF 3 0 1",
       "OFF line 1 holds only OFF: the vertex, face and edge counts go on the next line"},
      {"inline-body.off", "OFF 3 1 0\n" + tri + "3 0 1 2\n",
       "OFF line 1 holds only OFF: the vertex, face and edge counts go on the next line"},
      // The CI case: a vertical tab is a space to `>>`, so the words after the counts on line
      // 2 are vertex 0, line 5 a face of 2^31 - 1 corners where a line count saw a third vertex.
      {"vtab.off", "OFF\n3 1 0\v0 0 0\n1 0 0\n0 1 0\n2147483647 0 1 2\n",
       "OFF line 5: face 0's corner count must be a whole number 0 .. 4000002 (it is "
       "'2147483647')"},
      // OpenMesh has no comments: one where it reads a number stops its stream.
      {"comment.off", "OFF\n# made by hand\n3 1 0\n" + tri + "3 0 1 2\n",
       "OFF line 2: a '#' comment where OpenMesh reads the vertex count (its OFF reader has no "
       "comments: remove it)"},
      // Numbers `>>` would stop at: hexadecimal, past a float, a signed or fractional index.
      {"hex.off", "OFF\n3 1 0\n0x10 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
       "OFF line 3: a coordinate of vertex 0 '0x10' is not a decimal number within a float's "
       "range"},
      {"far.off", "OFF\n3 1 0\n1e39 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "'1e39' is not"},
      {"tiny.off", "OFF\n3 1 0\n1e-60 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "'1e-60' is not"},
      {"index.off", "OFF\n3 1 0\n" + tri + "3 0 1 3\n",
       "OFF line 6: face 0's vertex number must be a whole number 0 .. 2 (it is '3')"},
      {"fraction.off", "OFF\n3 1 0\n" + tri + "3 0 1.5 2\n", "(it is '1.5')"},
      {"short.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n", "the file ends before a coordinate of vertex 2"},
      // A colour after a face that is not the last: OpenMesh would read it as the next face.
      {"colour.off", "OFF\n3 2 0\n" + tri + "3 0 1 2 255 0 0\n3 0 2 1 255 0 0\n",
       "OFF line 6: face 0 has 3 words after its 3 vertex numbers (a colour?): OpenMesh would "
       "read them as the next face (face colours need a COFF header)"},
      // The rest of a vertex line is trimmed one character at a time, each a copy of the rest:
      // 40,000 spaces cost 1.6 GB of copies; under COFF, more than 6 items are printed as an
      // error.
      {"padded.off",
       "OFF\n3 1 0\n0 0 0" + std::string(40000, ' ') + "x\n1 0 0\n0 1 0\n" + "3 0 1 2\n",
       "OFF line 3: too many spaces round the words after vertices and faces"},
      {"colours.off", "COFF\n3 1 0\n0 0 0 1 2 3 4 5 6 7\n1 0 0\n0 1 0\n3 0 1 2\n",
       "OFF line 3: a colour of 7 items after the numbers"},
  };
  for (const Refused& c : cases) {
    write_file_atomic(dir + "/" + c.name, c.text);
    std::string e = "(read)";
    try {
      read_mesh_file(dir + "/" + c.name);
    } catch (const InputError& x) {
      e = x.what();
    }
    EXPECT_EQ(e.find('\n'), std::string::npos) << c.name;
    EXPECT_NE(e.find(c.message), std::string::npos) << c.name << ": " << e;
  }
  // What OpenMesh reads well is read: counts and coordinates across lines, a comment after a
  // vertex (the rest of its line is skipped), face colours under COFF, a colour after the
  // last face, NOFF's normals.
  const auto triangles = [&](const std::string& name, const std::string& text) {
    write_file_atomic(dir + "/" + name, text);
    return read_mesh_file(dir + "/" + name).triangles.size();
  };
  EXPECT_EQ(triangles("split.off",
                      "OFF\n3\n2 0 0 0 0\n1 0 0 # a vertex\n0 1 0\n3 0 1\n2\n"
                      "3 0 2 1\n"),
            2u);
  EXPECT_EQ(triangles("coff.off",
                      "COFF\n3 2 0\n0 0 0 9 9 9\n1 0 0 9 9 9\n0 1 0 9 9 9\n"
                      "3 0 1 2 255 0 0\n3 0 2 1 255 0 0\n"),
            2u);
  EXPECT_EQ(triangles("last.off", "OFF\n3 1 0\n" + tri + "3 0 1 2 255 0 0\n"), 1u);
  EXPECT_EQ(triangles("noff.off",
                      "NOFF\n3 1 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n"
                      "3 0 1 2\n"),
            1u);
}

}  // namespace
}  // namespace strand::slicer
