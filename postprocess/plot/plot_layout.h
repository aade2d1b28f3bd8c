// From an imported SVG drawing to a plotting Toolpath: pen assignment, placement on the
// machine's paper (fit, scale, offset, mirror), flattening within the tolerance budget,
// hatch fills, and the check that every point can be drawn.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "machines/profile.h"
#include "postprocess/plot/fill.h"
#include "slicer/svg_import.h"
#include "slicer/toolpath.h"

namespace strand::post {

struct PlotOptions {
  std::optional<slicer::Vec2> fit_mm;        // fit into W x H keeping aspect
  double scale = 1.0;                        // times the SVG's physical size (without fit)
  slicer::Vec2 offset_mm = slicer::Vec2::Zero();  // added after centring
  bool mirror = false;                       // mirror left-right (drawing on glass)
  double tolerance_mm = 0.05;                // end-to-end bound: flattening + bow + rounding
  std::string pens;                          // "key=pen,..." (group id, layer label, colour)
  bool order = true;
  FillStyle fill = FillStyle::Hatch;         // what a filled shape gets besides its outline
  // Per pen (pen 1 first; the last value holds for the pens after it). Spacing empty = the
  // pen's line width.
  std::vector<double> hatch_angle_deg = {45.0};
  std::vector<double> hatch_spacing_mm;
};

// The value of a per-pen list for the 1-based `pen`: its entry, the last entry past the end,
// `fallback` when the list is empty.
double per_pen(const std::vector<double>& values, int pen, double fallback);

// Points of the laid-out drawing (flattened outlines, plus fill lines) are bounded before
// flattening and again before filling: more would take minutes and gigabytes to plan and
// write (4 million points is about 100 MB of G-code).
inline constexpr double kMaxPlotPoints = 4e6;
// --fit never scales a drawing up more than this (a drawing a millionth of the box).
inline constexpr double kMaxFitScale = 1e6;

// Share of the tolerance spent on curve flattening; the rest goes to the kinematic bow of
// straight segments and to number rounding.
inline constexpr double kFlattenShare = 0.5;

// Which 1-based pen each shape uses: --pens rules first (group ids nearest first, then layer
// labels, then stroke or fill colour), else a group id m1..m9 as in Scribit, else pen 1.
// Throws InputError for a malformed rule or a pen the machine lacks.
std::vector<int> assign_pens(const slicer::SvgDrawing& d, const std::string& rules,
                             int machine_pens);

// The colour each pen draws in ("#rrggbb"; pen 1 first, as many as the highest pen used):
// the stroke colour of its first stroked shape, else the fill colour of its first filled
// one, else empty (a pen no shape uses, or a colour the drawing does not give).
std::vector<std::string> pen_colours(const slicer::SvgDrawing& d, const std::vector<int>& pens);

// The placed, flattened drawing as one layer of reversible Feature::Pen strokes (tool =
// 0-based pen), with derived["pen_colours"] as pen_colours gives. Throws InputError if nothing is drawable, a point cannot be reached (checked
// on the outlines before any fill), the points would pass kMaxPlotPoints (checked before
// flattening and before filling) or a fill fails (naming the shape).
slicer::Toolpath layout_plot(const slicer::SvgDrawing& d, const machines::MachineProfile& m,
                             const PlotOptions& o);

}  // namespace strand::post
