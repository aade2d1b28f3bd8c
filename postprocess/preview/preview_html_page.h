// The HTML preview's page: markup, style and the inline viewer script, with @TITLE@ and
// @DATA@ (the scene as JSON) to fill in. Kept apart from the data so each reads on its own.
#pragma once

#include <string>

namespace strand::post {

// The viewer: a 2D top view with a layer slider for planar scenes (data "dim": 2); an orbit
// view for 3D scenes ("dim": 3): drag to orbit, shift-drag to pan, wheel to zoom, the
// substrate ("substrate": {"v": xyz..., "t": ijk...}) drawn translucent, path segments
// behind it drawn first so it veils them. The URL hash "#yaw=A&pitch=B" (degrees),
// "layer=N" and "only=1" (this layer only) set the first view.
const std::string& html_page_template();

}  // namespace strand::post
