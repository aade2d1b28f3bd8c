// The options of one plot, shared by `strand plot` and the workbench's POST /api/plot: the
// parameter table (flags and form fields alike), its resolved values as plot and lettering
// options, and a traced image laid into a plot request with the command's pen rules.
#pragma once

#include <nlohmann/json.hpp>

#include "jobs/plot_pipeline.h"
#include "jobs/trace_input.h"
#include "postprocess/plot/plot_layout.h"
#include "slicer/params.h"
#include "slicer/text_layout.h"

namespace strand::jobs {

// fit, scale, offset, tolerance, pens, fill, hatch-angle, text, font, text-width, hatch-spacing.
const slicer::ParamTable& plot_table();

// Values resolved against plot_table(); `mirror` left-right, `order` merges and reorders.
post::PlotOptions plot_options(const nlohmann::json& resolved, bool mirror, bool order);

// How <text> is drawn (the text, font and text-width values). Throws InputError for a font
// of the other kind.
slicer::TextOptions text_options(const nlohmann::json& resolved);

// The traced image as the request's drawing, its trace values in the report and its note;
// unless the user chose hatch angles (`hatch_angle_given`), level k hatches at
// 45 + 180 (k - 1) / N degrees so darker areas, covered by more levels, cross-hatch.
// Throws InputError when nothing was traced (`label` names the image).
void use_traced(PlotRequest& request, const TracedImage& traced,
                const nlohmann::json& trace_resolved, bool hatch_angle_given,
                const std::string& label);

}  // namespace strand::jobs
