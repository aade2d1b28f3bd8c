// Headers of mesh files checked before a reader trusts them: OpenMesh's PLY reader sizes its
// tables from the header, and a malformed property line made it allocate 2.4 GB (a 507-byte
// file found by mesh_fuzz).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace strand::slicer {

// Bytes at the start of a PLY file searched for its `end_header` line.
inline constexpr std::size_t kMaxPlyHeaderBytes = 64 * 1024;

// Throws InputError "mesh = PATH: PLY header ..." unless the header is text, starts with
// `ply`, has one `format ascii|binary_little_endian|binary_big_endian 1.0` line, only
// `comment`/`obj_info`/`element NAME COUNT`/`property TYPE NAME`/`property list TYPE TYPE
// NAME` lines (each property after an element line, list counts of an integer type),
// element counts the file's `size_bytes` can hold, and ends with `end_header`; then walks the
// body (mesh_header_ply.h): every element and list count bounded by the bytes left and by
// kMaxMeshVertices / kMaxMeshTriangles before OpenMesh allocates for it.
void vet_ply_header(const std::string& path, std::uintmax_t size_bytes);

// OpenMesh's ASCII OFF reader takes every number with `>>`: where one does not parse, every
// later read keeps its variable as it was, and the face loop reran a stale corner count for
// each face left (2^31 corners took 8 GB: mesh_fuzz). Throws InputError "mesh = PATH: OFF ..."
// unless a walk over the words in OpenMesh's own order (mesh_header_off.cpp) reads a header
// line of [ST][C][N]OFF alone, three counts, every vertex's coordinates (decimal, finite as a
// float) and every face's corner count and vertex numbers (whole, each naming a vertex of the
// file) before the file ends, with no `#` comment where a number is read, no words after a
// face that OpenMesh would take for the next one, at most kMaxMeshVertices vertices and faces
// making at most kMaxMeshTriangles triangles.
void vet_off_file(const std::string& path);

// Readers drop or merge vertices with NaN or infinite coordinates and then report "no
// triangles" or "open mesh". Throws InputError "mesh = PATH: ... not finite (NaN or
// infinity)" naming the vertex (binary STL) or the line (STL, OBJ, OFF and ASCII PLY text)
// where a vertex coordinate is not a finite number, and "PLY line N: 'x' is not a number" for
// a word in an ASCII PLY body (OpenMesh spun for minutes on one). `ext` is ".stl", ".obj",
// ".off" or ".ply".
void vet_finite_vertices(const std::string& path, const std::string& ext,
                         std::uintmax_t size_bytes);

// OpenMesh's OBJ reader aborts (an assertion) on a face line none of whose corners names a
// vertex (mesh_fuzz). Throws InputError "mesh = PATH: OBJ line N: ..." unless every `f` line
// has at least 3 corners, each starting with a non-zero vertex index, and the faces make at
// most kMaxMeshTriangles triangles (n - 2 for a face of n corners).
void vet_obj_faces(const std::string& path);

// A space to `>>` (isspace in the C locale): space, tab, line end, vertical tab, form feed.
inline bool is_word_space(char c) { return c == ' ' || (c >= '\t' && c <= '\r'); }

// The words of `line` as `>>` splits them (at is_word_space): views into `line`.
void split_words(std::string_view line, std::vector<std::string_view>& words);

}  // namespace strand::slicer
