// 3D preview as binary glTF (.glb, written with tinygltf): deposited strands as tubes (or
// lines) coloured by feature, one node per layer under a root node, so any glTF viewer
// opens it and can hide layers.
#pragma once

#include <string>

#include "postprocess/preview/preview_scene.h"

namespace strand::post {

struct GlbOptions {
  bool tubes = true;      // false: line primitives (smaller files, 1 px wide in most viewers)
  int tube_sides = 6;     // polygon around each segment, radius = half the bead width
};

// The root node "toolpath" turns Strand's z-up millimetres into glTF's y-up metres; its
// children are the "substrate" node when the scene has one (a translucent, double-sided
// mesh: alpha-blended material "substrate", smooth normals), then "layer N" nodes, one per
// layer holding deposits. Travel moves are left out.
std::string render_glb(const PreviewScene& scene, const GlbOptions& options = {});

}  // namespace strand::post
