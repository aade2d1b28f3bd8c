// Pen assignment, placement, flattening, fills and reachability for `strand plot`.
#include "postprocess/plot/plot_layout.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "machines/plotter_kinematics.h"
#include "postprocess/plot/fill.h"
#include "slicer/input_error.h"
#include "slicer/params.h"
#include "slicer/svg_syntax.h"

namespace strand::post {

namespace {

using slicer::Affine;
using slicer::Vec2;

struct Rule {
  std::string key;
  int pen = 1;
};

std::vector<Rule> parse_rules(const std::string& text) {
  std::vector<Rule> rules;
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t comma = std::min(text.find(',', at), text.size());
    const std::string item = text.substr(at, comma - at);
    const auto eq = item.rfind('=');
    int pen = 0;
    if (eq != std::string::npos) {
      try {
        pen = std::stoi(item.substr(eq + 1));
      } catch (const std::exception&) {
        pen = 0;
      }
    }
    if (eq == std::string::npos || eq == 0 || pen < 1) {
      throw InputError("plot.pens = \"" + text + "\": each rule must be KEY=PEN with PEN >= 1 (KEY a group id, layer label or colour)");
    }
    rules.push_back({item.substr(0, eq), pen});
    at = comma + 1;
  }
  return rules;
}

int default_pen(const slicer::SvgShape& s) {
  for (const auto& id : s.group_ids) {
    if (id.size() == 2 && id[0] == 'm' && id[1] >= '1' && id[1] <= '9') return id[1] - '0';
  }
  return 1;
}

int rule_pen(const slicer::SvgShape& s, const std::vector<Rule>& rules) {
  const auto match = [&](const std::string& key) {
    for (const auto& r : rules) {
      if (r.key == key) return r.pen;
    }
    return 0;
  };
  for (const auto& id : s.group_ids) {
    if (int p = match(id)) return p;
  }
  for (const auto& l : s.layer_labels) {
    if (int p = match(l)) return p;
  }
  for (const auto& c : {s.stroke_color, s.fill_color}) {
    if (c.empty()) continue;
    for (const auto& r : rules) {
      if (slicer::normalise_color(r.key) == c) return r.pen;
    }
  }
  return 0;
}

// A count or factor for a message: three significant digits ("1.63e+302", "5.26e+07").
std::string count_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

// Exact bounds of the drawing under m (a similarity: bounds map onto bounds).
std::pair<Vec2, Vec2> bounds_of(const slicer::SvgDrawing& d, const Affine& m) {
  Vec2 lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
  for (const auto& s : d.shapes) {
    for (const auto& p : s.paths) {
      const auto [plo, phi] = slicer::curve_bounds(p);
      const Vec2 a = m.apply(plo), b = m.apply(phi);
      lo = lo.cwiseMin(a.cwiseMin(b));
      hi = hi.cwiseMax(a.cwiseMax(b));
    }
  }
  return {lo, hi};
}

// SVG (mm, y down) -> paper frame of the machine, centred in its drawable area.
Affine placement(const slicer::SvgDrawing& d, const machines::MachineProfile& m, const PlotOptions& o) {
  Affine base;
  base.linear << (o.mirror ? -1.0 : 1.0), 0, 0, (machines::paper_y_down(m.plotter.setup.kind) ? 1.0 : -1.0);
  const auto [lo, hi] = bounds_of(d, base);
  const Vec2 size = hi - lo;
  double s = o.scale;
  if (o.fit_mm) {
    s = INFINITY;
    if (size.x() > 0) s = std::min(s, o.fit_mm->x() / size.x());
    if (size.y() > 0) s = std::min(s, o.fit_mm->y() / size.y());
    if (!std::isfinite(s)) s = 1.0;
    if (s > kMaxFitScale) {
      throw InputError("plot.fit = " + slicer::short_number(o.fit_mm->x()) + "x" +
                       slicer::short_number(o.fit_mm->y()) + ": the drawing is only " +
                       slicer::short_number(size.x()) + " x " + slicer::short_number(size.y()) +
                       " mm; fitting it would scale it " + count_text(s) + " times (at most " +
                       slicer::short_number(kMaxFitScale) + ")");
    }
  }
  const auto [alo, ahi] = machines::drawable_area(m.plotter);
  const Vec2 centre = (alo + ahi) / 2 + o.offset_mm;
  Affine place;
  place.linear = s * Eigen::Matrix2d::Identity();
  place.offset = centre - s * (lo + hi) / 2;
  return slicer::compose(place, base);
}

slicer::Stroke stroke_of(const slicer::Polyline& pl, int tool, double width_mm) {
  slicer::Stroke s;
  s.start_mm = pl.front();
  for (std::size_t i = 1; i < pl.size(); ++i) {
    if ((pl[i] - pl[i - 1]).norm() > 0.0) s.segments.push_back(slicer::line_to(pl[i], slicer::Feature::Pen));
  }
  s.width_mm = width_mm;
  s.tool = tool;
  s.reversible = true;
  return s;
}

std::string point_text(const Vec2& p) {
  return "(" + slicer::short_number(std::round(p.x() * 1000) / 1000) + ", " +
         slicer::short_number(std::round(p.y() * 1000) / 1000) + ") mm";
}

void check_reachable(const std::vector<slicer::Polyline>& lines,
                     const machines::MachineProfile& m) {
  for (const auto& pl : lines) {
    for (const auto& p : pl) {
      if (const auto why = machines::unreachable_reason(m.plotter, p)) {
        throw InputError("plot: the drawing does not fit " + m.name + ": point " + point_text(p) +
                         ": " + *why + " (use --fit, --scale or --offset)");
      }
    }
  }
}

// Flattening is bounded before it starts: the placement is a similarity of scale s, so a
// curve flattened to tol on paper is the original flattened to tol / s.
void check_outline_budget(const slicer::SvgDrawing& d, double scale, const PlotOptions& o) {
  double points = 0.0;
  for (const auto& shape : d.shapes) {
    for (const auto& p : shape.paths)
      points += slicer::flatten_point_bound(p, o.tolerance_mm * kFlattenShare / scale);
  }
  if (points > kMaxPlotPoints) {
    throw InputError("plot.tolerance = " + slicer::short_number(o.tolerance_mm) +
                     ": the curves would flatten into up to " + count_text(points) +
                     " points (at most " + slicer::short_number(kMaxPlotPoints) +
                     "); use a larger tolerance, a smaller scale or a simpler drawing");
  }
}

std::string describe(const slicer::SvgShape& s, std::size_t index) {
  return "<" + s.element + (s.id.empty() ? "" : " id=\"" + s.id.substr(0, 40) + "\"") +
         "> (shape " + std::to_string(index + 1) + ")";
}

// Shapes from any source (SVG, text layout, tracing) are within kMaxCoordinateMm before
// their bounds and point counts are computed from them.
void check_coordinates(const slicer::SvgDrawing& d) {
  for (std::size_t i = 0; i < d.shapes.size(); ++i) {
    for (const auto& p : d.shapes[i].paths) {
      const double m = slicer::max_abs_coordinate(p);
      if (!(m <= slicer::kMaxCoordinateMm)) {
        throw InputError(
            "plot: " + describe(d.shapes[i], i) + ": a coordinate is " +
            (std::isfinite(m) ? slicer::short_number(m) + " mm" : std::string("not finite")) +
            " from the origin (at most " + slicer::short_number(slicer::kMaxCoordinateMm) + " mm)");
      }
    }
  }
}

// The fill of a filled shape, then its outline (drawn last so it covers the line ends) unless
// the shape is stroked anyway.
std::vector<slicer::Polyline> fill_lines(const std::vector<slicer::Polyline>& outlines,
                                         const slicer::SvgShape& shape, int pen, double width_mm,
                                         const PlotOptions& o) {
  const double spacing = per_pen(o.hatch_spacing_mm, pen, width_mm);
  std::vector<slicer::Polyline> lines;
  if (o.fill == FillStyle::Hatch) {
    lines = hatch_fill(outlines, shape.evenodd, spacing, per_pen(o.hatch_angle_deg, pen, 45.0));
  } else if (o.fill == FillStyle::Concentric) {
    lines = concentric_fill(outlines, shape.evenodd, spacing);
  }
  if (o.fill != FillStyle::None && !shape.stroked) {
    for (auto& pl : fill_outline(outlines)) lines.push_back(std::move(pl));
  }
  return lines;
}

// The fills are bounded before any is computed: outline points plus every filled shape's
// fill_point_bound stay within kMaxPlotPoints.
void check_fill_budget(const slicer::SvgDrawing& d,
                       const std::vector<std::vector<slicer::Polyline>>& outlines,
                       const std::vector<int>& pens, double width_mm, const PlotOptions& o,
                       double points) {
  for (std::size_t i = 0; i < d.shapes.size(); ++i) {
    if (!d.shapes[i].filled) continue;
    points += fill_point_bound(outlines[i], o.fill, per_pen(o.hatch_spacing_mm, pens[i], width_mm),
                               per_pen(o.hatch_angle_deg, pens[i], 45.0));
  }
  if (points > kMaxPlotPoints) {
    throw InputError("plot.hatch-spacing: the outlines and fills would draw up to " +
                     count_text(points) + " points (at most " +
                     slicer::short_number(kMaxPlotPoints) +
                     "); use a larger --hatch-spacing, --fill outline or a smaller drawing");
  }
}

// Every shape's outlines on paper, each checked for reach before any fill is computed;
// `points` counts them.
std::vector<std::vector<slicer::Polyline>> placed_outlines(const slicer::SvgDrawing& d,
                                                           const Affine& to_paper,
                                                           const machines::MachineProfile& m,
                                                           const PlotOptions& o, double& points) {
  std::vector<std::vector<slicer::Polyline>> outlines(d.shapes.size());
  for (std::size_t i = 0; i < d.shapes.size(); ++i) {
    for (const auto& p : d.shapes[i].paths) {
      outlines[i].push_back(
          slicer::flatten(slicer::transformed(p, to_paper), o.tolerance_mm * kFlattenShare));
      points += static_cast<double>(outlines[i].back().size());
    }
    check_reachable(outlines[i], m);
  }
  return outlines;
}

}  // namespace

double per_pen(const std::vector<double>& values, int pen, double fallback) {
  if (values.empty()) return fallback;
  return values[std::min<std::size_t>(std::max(pen, 1) - 1, values.size() - 1)];
}

std::vector<int> assign_pens(const slicer::SvgDrawing& d, const std::string& rules_text, int machine_pens) {
  const auto rules = parse_rules(rules_text);
  std::vector<int> pens;
  for (const auto& s : d.shapes) {
    int pen = rule_pen(s, rules);
    if (pen == 0) pen = default_pen(s);
    if (pen > machine_pens) {
      throw InputError("plot.pens: a shape maps to pen " + std::to_string(pen) + " but the machine has " +
                       std::to_string(machine_pens) + " pen(s)");
    }
    pens.push_back(pen);
  }
  return pens;
}

slicer::Toolpath layout_plot(const slicer::SvgDrawing& d, const machines::MachineProfile& m,
                             const PlotOptions& o) {
  if (!m.plotter.enabled) throw InputError("machine = " + m.name + ": not a plotter (no \"plotter\" block in its profile)");
  if (d.shapes.empty()) throw InputError("plot: the SVG has nothing drawable (no visible stroked or filled shapes)");
  check_coordinates(d);
  const std::vector<int> pens = assign_pens(d, o.pens, m.plotter.pen.count);
  const Affine to_paper = placement(d, m, o);
  check_outline_budget(d, std::abs(to_paper.linear(0, 0)), o);
  const double width = m.plotter.pen.width_mm;
  double points = 0.0;
  const auto outlines = placed_outlines(d, to_paper, m, o, points);
  check_fill_budget(d, outlines, pens, width, o, points);
  slicer::Toolpath t;
  t.generator = "plot";
  t.layers.push_back({0.0, 0.0, {}});
  auto& strokes = t.layers[0].strokes;
  for (std::size_t i = 0; i < d.shapes.size(); ++i) {
    const auto& shape = d.shapes[i];
    const int tool = pens[i] - 1;
    if (shape.filled) {
      std::vector<slicer::Polyline> lines;
      try {
        lines = fill_lines(outlines[i], shape, pens[i], width, o);
      } catch (const InputError& e) {
        throw InputError("plot: " + describe(shape, i) + ": " + e.what());
      }
      check_reachable(lines, m);
      for (const auto& pl : lines) strokes.push_back(stroke_of(pl, tool, width));
    }
    if (shape.stroked) {
      for (const auto& pl : outlines[i]) strokes.push_back(stroke_of(pl, tool, width));
    }
  }
  std::erase_if(strokes, [](const slicer::Stroke& s) { return s.segments.empty(); });
  if (strokes.empty())
    throw InputError("plot: the SVG has nothing drawable (every shape is empty after placement)");
  const auto [lo, hi] = slicer::bounds(t);
  t.derived["drawing_width_mm"] = hi.x() - lo.x();
  t.derived["drawing_height_mm"] = hi.y() - lo.y();
  t.derived["scale"] = to_paper.linear.cwiseAbs().maxCoeff();  // times true size
  t.derived["pen_colours"] = pen_colours(d, pens);
  return t;
}

std::vector<std::string> pen_colours(const slicer::SvgDrawing& d, const std::vector<int>& pens) {
  const auto rgb = [](const std::string& c) {  // "#rrggbb" only (no gradients, no names)
    return c.size() == 7 && c[0] == '#' &&
           c.find_first_not_of("0123456789abcdef", 1) == std::string::npos;
  };
  std::vector<std::string> stroke, fill;
  for (std::size_t i = 0; i < d.shapes.size() && i < pens.size(); ++i) {
    const auto k = static_cast<std::size_t>(std::max(pens[i], 1));
    if (stroke.size() < k) stroke.resize(k), fill.resize(k);
    const auto& s = d.shapes[i];
    if (s.stroked && stroke[k - 1].empty() && rgb(s.stroke_color)) stroke[k - 1] = s.stroke_color;
    if (s.filled && fill[k - 1].empty() && rgb(s.fill_color)) fill[k - 1] = s.fill_color;
  }
  for (std::size_t k = 0; k < stroke.size(); ++k) {
    if (stroke[k].empty()) stroke[k] = fill[k];
  }
  return stroke;
}

}  // namespace strand::post
