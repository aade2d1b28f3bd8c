// DIR/index.html for a sweep: a contact sheet with one card per point (thumbnail, varied
// parameters, key figures, check, links to the G-code and preview), sortable in the page.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace strand::jobs {

// Self-contained HTML (inline CSS and script, no network); paths are relative to DIR. Once
// loaded, #status reads "cards: N, thumbnails shown: M".
std::string sweep_index_html(const nlohmann::json& manifest);

}  // namespace strand::jobs
