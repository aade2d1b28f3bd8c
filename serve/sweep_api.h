// Sweeps kept in the gallery as one group with their contact sheet: POST /api/sweeps and
// GET /api/sweeps/{id}/files/{path} (Api::State::route_sweeps, sweep_api.cpp).
#pragma once

#include <cstddef>

namespace strand::serve {

// Points (not dropped by `where`) of a sweep the workbench runs; larger ones are for
// `strand sweep`. Each point is a job within the bounds of `strand job`.
inline constexpr std::size_t kMaxServedSweepPoints = 64;

}  // namespace strand::serve
