// The tail shared by `strand plot`, `strand text` and traced images: a drawing (shapes in
// mm) laid out, merged, ordered, planned and emitted for one plotter, with its report and
// summary. Nothing is written here; callers write every output atomically at the end.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "machines/profile.h"
#include "postprocess/plot/plot_layout.h"
#include "slicer/progress_listener.h"
#include "slicer/svg_import.h"
#include "slicer/text_layout.h"
#include "slicer/toolpath.h"

namespace strand::jobs {

struct PlotRequest {
  std::string input;              // file name (or label) for the header and the report
  slicer::SvgDrawing drawing;     // text already turned into shapes
  post::PlotOptions options;
  nlohmann::json parameters = nlohmann::json::object();  // resolved flags, for the report
  // Extra rows for the summary, header and report ("text", "2 elements, 31 glyphs ...").
  std::vector<std::pair<std::string, std::string>> notes;
};

struct PlotResult {
  slicer::Toolpath toolpath;      // ordered strokes on the paper
  std::string gcode;
  nlohmann::json report;
  std::string summary;            // what the command prints
};

// Turns the drawing's texts into shapes with `o` (or lists them as skipped for
// TextMode::None) and adds the "text" note. Throws InputError for a missing font.
void draw_text_into(PlotRequest& request, const slicer::TextOptions& o);

// Throws InputError (nothing drawable, out of reach, bad pens, tolerance, fill budget).
// Takes the request by value: its shapes are dropped once laid out, before ordering and
// planning (a 300,000-line drawing holds about a third of the command's peak memory).
// `progress` (may be null) is told the phases: laying out, ordering, planning, G-code.
PlotResult plot_drawing(PlotRequest request, const machines::MachineProfile& m,
                        slicer::Progress* progress = nullptr);

}  // namespace strand::jobs
