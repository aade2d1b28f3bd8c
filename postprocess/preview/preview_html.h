// Interactive HTML preview: one self-contained file (no network) with a layer slider,
// feature (or layer) colours, zoom/pan, a travel toggle and a scale bar in mm, drawn on a
// canvas by an inline script.
#pragma once

#include <string>

#include "postprocess/preview/preview_scene.h"

namespace strand::post {

// `title` names the source file in the page. The script fills #status with
// "drawn: N paths, layers A-B" once drawn, or "error: ..." if anything throws.
std::string render_html(const PreviewScene& scene, const std::string& title);

}  // namespace strand::post
