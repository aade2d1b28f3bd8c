// Interactive HTML preview: one self-contained file (no network) with a layer slider,
// feature (or layer) colours, zoom/pan, a travel toggle and a scale bar in mm, drawn on a
// canvas by an inline script: a top view for planar scenes, an orbit view over the
// translucent substrate for 3D ones (is_3d). It fits the part's deposits (not purge lines
// before the first layer, nor travels) and refits on "this layer only".
#pragma once

#include <string>

#include "postprocess/preview/preview_scene.h"

namespace strand::post {

// `title` names the source file in the page. The script fills #status with
// "drawn: N paths, layers A-B" (3D: followed by " (3D orbit view)") once drawn, or
// "error: ..." if anything throws.
std::string render_html(const PreviewScene& scene, const std::string& title);

}  // namespace strand::post
