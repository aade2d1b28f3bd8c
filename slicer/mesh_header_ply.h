// A PLY file's layout as its header declares it, and the walk over its body that bounds every
// element and list count before OpenMesh allocates for them (a 331-byte binary file whose one
// face claimed 2^31 - 1 indices made OpenMesh take 8 GB and a minute).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace strand::slicer {

enum class PlyFormat { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct PlyProperty {
  bool list = false;
  int count_bytes = 0;  // list: size of the count (1, 2 or 4)
  bool count_signed = false;
  int bytes = 0;  // scalar: its size; list: one entry's size
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

struct PlyLayout {
  PlyFormat format = PlyFormat::Ascii;
  std::vector<PlyElement> elements;
  std::uint64_t body_offset = 0;  // the first byte after the end_header line
};

// Bytes of a PLY type name (char .. float64); 0 for anything else.
int ply_type_bytes(const std::string& type);

// Throws InputError "mesh = PATH: PLY ..." when an element's records cannot fit in the bytes
// after the header, a list count is negative or claims more entries than the bytes left (or,
// in ASCII, the words left) can hold, the file ends inside an element, the vertices exceed
// kMaxMeshVertices or the faces' triangles (n - 2 per face of n corners) kMaxMeshTriangles.
// Reads the body once, keeping nothing.
void vet_ply_body(const std::string& path, std::uintmax_t size_bytes, const PlyLayout& layout);

}  // namespace strand::slicer
