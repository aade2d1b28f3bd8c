// One preview file from a scene, its format chosen by the file name's extension: the one
// dispatch that `strand preview`, `strand slice --preview` and the robot outputs share.
#pragma once

#include <string>

#include "postprocess/preview/preview_gltf.h"
#include "postprocess/preview/preview_image.h"
#include "postprocess/preview/preview_scene.h"

namespace strand::post {

enum class PreviewFormat { Png, Svg, Html, Glb };

// .png, .svg, .html or .glb; throws InputError naming `key` (e.g. "preview") otherwise.
PreviewFormat preview_format(const std::string& path, const std::string& key);

struct PreviewFileOptions {
  ImageOptions image;       // png, svg
  GlbOptions glb;           // glb
  std::string title;        // html: the page title (usually the G-code file name)
};

std::string render_preview(const PreviewScene& scene, PreviewFormat format,
                           const PreviewFileOptions& options);

}  // namespace strand::post
