// Images as drawings: the trace flags (one table for `strand trace` and `strand plot
// --trace`) and a traced image as pen layers (level k in group m<k>, so on pen k).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "slicer/params.h"
#include "slicer/progress_listener.h"
#include "slicer/svg_export.h"
#include "slicer/trace.h"

namespace strand::jobs {

const slicer::ParamTable& trace_table();
slicer::TraceOptions trace_options(const nlohmann::json& resolved);

struct TracedImage {
  slicer::Trace trace;
  std::vector<slicer::SvgLayer> layers;  // one per level: filled, even-odd, grey of its level
  std::string summary;                   // "2 levels at grey 0.48, 0.24; 31 + 12 outlines"
};

// Reads, decodes and traces `path`. Throws InputError for files that are no image.
// `progress` (may be null) is told the phases: decoding, tracing.
TracedImage trace_file(const std::string& path, const slicer::TraceOptions& o,
                       slicer::Progress* progress = nullptr);
// The same for an image already in memory; `label` names it in messages.
TracedImage trace_bytes(const std::string& bytes, const std::string& label, const slicer::TraceOptions& o,
                        slicer::Progress* progress = nullptr);

// The layers as an imported drawing (what `strand plot` lays out).
slicer::SvgDrawing drawing_of(const std::vector<slicer::SvgLayer>& layers, const slicer::Vec2& size_mm);

}  // namespace strand::jobs
