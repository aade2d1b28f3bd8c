// The 3D viewer as one self-contained HTML file (`strand preview -o x.html`): the viewer's
// script (three.js bundled in, web/viewer.js) and the data (viewer_data.h: the index as JSON,
// the layer blocks in base64) inline, so it opens from disk with no network.
#pragma once

#include <string>

#include "postprocess/preview/viewer_data.h"

namespace strand::post {

// The bundled viewer script (generated at build time from web/viewer.js and three.js).
const std::string& viewer_script();

// `title` names the source file. The page's #status reads "drawn: N segments, layers 0-L in
// T ms" once drawn, or "error: ..."; #stats holds the last shown layer's figures.
std::string render_viewer_html(const ViewerData& data, const std::string& title);

}  // namespace strand::post
