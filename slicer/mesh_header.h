// Headers of mesh files checked before a reader trusts them: OpenMesh's PLY reader sizes its
// tables from the header, and a malformed property line made it allocate 2.4 GB (a 507-byte
// file found by mesh_fuzz).
#pragma once

#include <cstdint>
#include <string>

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

// OpenMesh's OFF reader loops for as long as its counts say when a number does not parse (a
// garbled count line took minutes: mesh_fuzz). Throws InputError "mesh = PATH: OFF ..." unless
// the file is ASCII OFF whose every token outside `#` comments is a number, with vertex and
// face counts the file's `size_bytes` can hold (and at most kMaxMeshVertices vertices), each
// face line listing the corners its count says (OpenMesh sized the face from the count: 2^31
// took 8 GB), the faces making at most kMaxMeshTriangles triangles.
void vet_off_file(const std::string& path, std::uintmax_t size_bytes);

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

}  // namespace strand::slicer
