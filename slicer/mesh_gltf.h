// glTF 2.0 (.gltf with its buffers, or binary .glb) to Mesh with tinygltf: every triangle
// primitive of the default scene, node transforms applied, TEXCOORD_0 kept when present;
// glTF's +Y up becomes Strand's +Z up.
#pragma once

#include <string>

#include "slicer/mesh.h"

namespace strand::slicer {

// Throws InputError for a file tinygltf cannot load or that holds no triangles.
Mesh read_gltf(const std::string& path);

}  // namespace strand::slicer
