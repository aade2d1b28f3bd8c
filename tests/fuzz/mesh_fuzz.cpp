// Fuzz target: any bytes as a part or substrate mesh file, in the format the first byte picks
// (STL, OBJ, PLY, OFF through OpenMesh; glTF, GLB through tinygltf; a zip after it is 3MF
// through lib3mf), read, placed and prepared with and without --repair, strict and as a soup
// sliced into layers, as `strand slice` does. The readers take a path, so each input is written
// to a file in a private temporary directory first.
#include <unistd.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <string>

#include "slicer/input_error.h"
#include <filesystem>

#include "slicer/mesh_check.h"
#include "slicer/mesh_io.h"
#include "slicer/mesh_slicer.h"

namespace {

const std::string& scratch_dir() {
  static const std::string dir = [] {
    std::string pattern =
        (std::filesystem::temp_directory_path() / "strand-mesh-fuzz-XXXXXX").string();
    if (!mkdtemp(pattern.data())) std::abort();
    return pattern;
  }();
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace strand;
  static const std::array<const char*, 6> kExtensions = {".stl", ".obj",  ".ply",
                                                         ".off", ".gltf", ".glb"};
  if (size == 0) return 0;
  // A zip (3MF's container) after the first byte is read as 3MF, whatever that byte is.
  const bool zip = size >= 5 && data[1] == 'P' && data[2] == 'K';
  const std::string path =
      scratch_dir() + "/part" + (zip ? ".3mf" : kExtensions[data[0] % kExtensions.size()]);
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
  }
  try {
    const slicer::Mesh read = slicer::read_mesh_file(path);
    const slicer::Mesh placed = slicer::place_mesh(read, slicer::MeshPlacement{});
    for (const bool repair : {false, true}) {
      try {
        slicer::prepare_mesh(placed, repair, "part");
      } catch (const InputError&) {
      }
    }
    // The default path: defects reported, the soup sliced (a few layers over its height).
    try {
      const slicer::PreparedMesh p = slicer::prepare_mesh(placed, slicer::PrepareOptions{}, "part");
      const double height = slicer::bounds(p.mesh).size_mm().z();
      if (height > 0.0) slicer::slice_layers(p.mesh, height / 4.0, 4);
    } catch (const InputError&) {
    }
  } catch (const InputError&) {
  }
  unlink(path.c_str());
  return 0;
}
