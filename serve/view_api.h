// The 3D toolpath viewer's routes (Api::State::route_view, issue 34): the page /view/{id}, the
// bundled viewer script /assets/viewer.js (three.js inside, never a CDN), the index
// GET /api/jobs/{id}/view and the binary layer blocks GET /api/jobs/{id}/view/layers?from=A&to=B
// (postprocess/preview/viewer_data.h), built once per job into the job's folder.
#pragma once

#include <string>

namespace strand::serve {

// True for the paths Api::State::route_view answers.
bool is_view_path(const std::string& path);

}  // namespace strand::serve
