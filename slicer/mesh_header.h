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
// NAME` lines (each property after an element line), element counts the file's
// `size_bytes` can hold, and ends with `end_header`.
void vet_ply_header(const std::string& path, std::uintmax_t size_bytes);

// OpenMesh's OFF reader loops for as long as its counts say when a number does not parse (a
// garbled count line took minutes: mesh_fuzz). Throws InputError "mesh = PATH: OFF ..." unless
// the file is ASCII OFF whose every token outside `#` comments is a number, with vertex and
// face counts the file's `size_bytes` can hold.
void vet_off_file(const std::string& path, std::uintmax_t size_bytes);

}  // namespace strand::slicer
