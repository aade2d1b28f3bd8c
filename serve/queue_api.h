// The queue's routes (Api::State::route_queue): the page /queue, GET /api/ports,
// GET|POST /api/queue, POST /api/queue/{id}/start|pause|resume|cancel|home and GET /api/events
// (Server-Sent Events).
#pragma once

#include <string>

namespace strand::serve {

// True for the paths Api::State::route_queue answers.
bool is_queue_path(const std::string& path);

}  // namespace strand::serve
