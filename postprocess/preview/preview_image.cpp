// Cairo drawing shared by the PNG and SVG previews.
#include "postprocess/preview/preview_image.h"

#include <cairo-svg.h>
#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "slicer/input_error.h"
#include "slicer/params.h"

namespace strand::post {

namespace {

using slicer::Vec2;
using slicer::Vec3;

constexpr double kMarginPx = 24.0;      // free border around each panel's drawing
constexpr double kCaptionPx = 36.0;     // room at the bottom for the scale bar and caption
const double kCos30 = std::sqrt(3.0) / 2.0;

Vec2 project(const Vec3& p, PreviewView view) {
  if (view == PreviewView::Top) return {p.x(), -p.y()};
  // Isometric: x to the lower right, y to the upper right, z up (screen y grows down).
  return {(p.x() + p.y()) * kCos30, (p.y() - p.x()) * 0.5 - p.z()};
}

struct Panel {
  double x0 = 0, y0 = 0, w = 0, h = 0;  // px
  PreviewView view = PreviewView::Top;
  double scale = 1.0;                    // px per mm
  Vec2 offset = Vec2::Zero();            // px = offset + scale * projected
  Vec2 at(const Vec3& p) const { return offset + scale * project(p, view); }
};

bool visible(const PreviewPath& p, const ImageOptions& o) {
  return (o.travel || !p.travel) && (o.layer < 0 || p.layer == o.layer);
}

void fit(Panel& panel, const PreviewScene& s, const ImageOptions& o) {
  Vec2 lo(1e300, 1e300), hi(-1e300, -1e300);
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 c((corner & 1) ? s.max_mm.x() : s.min_mm.x(), (corner & 2) ? s.max_mm.y() : s.min_mm.y(),
                 (corner & 4) ? s.max_mm.z() : s.min_mm.z());
    const Vec2 q = project(c, panel.view);
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  const double room_w = panel.w - 2 * kMarginPx, room_h = panel.h - 2 * kMarginPx - (o.scale_bar ? kCaptionPx : 0);
  const Vec2 size = (hi - lo).cwiseMax(Vec2(1e-3, 1e-3));
  panel.scale = o.px_per_mm > 0 ? o.px_per_mm : std::min(room_w / size.x(), room_h / size.y());
  const Vec2 centre = 0.5 * (lo + hi);
  const Vec2 room_centre(panel.x0 + panel.w / 2, panel.y0 + kMarginPx + room_h / 2);
  panel.offset = room_centre - panel.scale * centre;
}

void set_colour(cairo_t* cr, const Rgb& c) { cairo_set_source_rgb(cr, c.r, c.g, c.b); }

void draw_paths(cairo_t* cr, const Panel& panel, const PreviewScene& s, const ImageOptions& o) {
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  const int layers = static_cast<int>(s.layer_z_mm.size());
  const double bead_px = std::max(1.0, (s.bead_width_mm > 0 ? s.bead_width_mm : 0.4) * panel.scale);
  for (const auto& p : s.paths) {
    if (!visible(p, o)) continue;
    if (p.travel) {
      cairo_set_source_rgba(cr, 0.45, 0.45, 0.45, 0.8);
      cairo_set_line_width(cr, 0.75);
    } else {
      set_colour(cr, o.colouring == PreviewColouring::Layer ? layer_colour(p.layer, layers) : feature_colour(p.feature));
      cairo_set_line_width(cr, bead_px);
    }
    const Vec2 a = panel.at(p.points_mm.front());
    cairo_move_to(cr, a.x(), a.y());
    for (std::size_t i = 1; i < p.points_mm.size(); ++i) {
      const Vec2 b = panel.at(p.points_mm[i]);
      cairo_line_to(cr, b.x(), b.y());
    }
    cairo_stroke(cr);
  }
}

// Circles around the marks of the visible layers, at the layer's height; touches first so a
// crossing at the same point stays red.
void draw_marks(cairo_t* cr, const Panel& panel, const PreviewScene& s, const ImageOptions& o) {
  const double radius_px = 7.0;
  cairo_set_line_width(cr, 2.0);
  for (bool crossings : {false, true}) {
    if (crossings) {
      cairo_set_source_rgb(cr, 0.88, 0.0, 0.0);
    } else {
      cairo_set_source_rgb(cr, 1.0, 0.55, 0.0);
    }
    for (const auto& m : o.marks) {
      if (m.crossing != crossings || (o.layer >= 0 && m.layer != o.layer)) continue;
      const bool known = m.layer >= 0 && m.layer < static_cast<int>(s.layer_z_mm.size());
      const double z = known ? s.layer_z_mm[static_cast<std::size_t>(m.layer)] : 0.0;
      const Vec2 c = panel.at(Vec3(m.at_mm.x(), m.at_mm.y(), z));
      cairo_new_sub_path(cr);
      cairo_arc(cr, c.x(), c.y(), radius_px, 0.0, 2 * M_PI);
      cairo_stroke(cr);
    }
  }
}

// 1, 2 or 5 times a power of ten, about a fifth of the panel.
double nice_length_mm(double panel_mm) {
  const double target = panel_mm / 5.0;
  const double p = std::pow(10.0, std::floor(std::log10(target)));
  for (double m : {5.0, 2.0, 1.0}) {
    if (m * p <= target) return m * p;
  }
  return p;
}

void draw_caption(cairo_t* cr, const Panel& panel, const ImageOptions& o) {
  const double len_mm = nice_length_mm((panel.w - 2 * kMarginPx) / panel.scale);
  // In the isometric view the bar lies along the projected x axis, where 1 mm is cos 30.
  const double len_px = len_mm * panel.scale * (panel.view == PreviewView::Top ? 1.0 : kCos30);
  const double x = panel.x0 + kMarginPx, y = panel.y0 + panel.h - kMarginPx;
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
  cairo_set_line_width(cr, 2.0);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
  cairo_move_to(cr, x, y - 6);
  cairo_line_to(cr, x, y);
  cairo_line_to(cr, x + len_px, y);
  cairo_line_to(cr, x + len_px, y - 6);
  cairo_stroke(cr);
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, 13.0);
  std::string label = slicer::short_number(len_mm) + " mm";
  label += panel.view == PreviewView::Top ? "   top view" : " (along x)   isometric view";
  if (o.layer >= 0) label += ", layer " + std::to_string(o.layer);
  cairo_move_to(cr, x + len_px + 10, y);
  cairo_show_text(cr, label.c_str());
}

std::vector<Panel> layout(const PreviewScene& s, const ImageOptions& o) {
  std::vector<Panel> panels;
  const double w = o.width_px, h = o.height_px;
  if (o.view == PreviewView::Both) {
    panels.push_back({0, 0, w / 2, h, PreviewView::Top});
    panels.push_back({w / 2, 0, w / 2, h, PreviewView::Iso});
  } else {
    panels.push_back({0, 0, w, h, o.view});
  }
  for (auto& p : panels) fit(p, s, o);
  return panels;
}

void draw(cairo_t* cr, const PreviewScene& s, const ImageOptions& o) {
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  for (const auto& panel : layout(s, o)) {
    draw_paths(cr, panel, s, o);
    if (!o.marks.empty()) draw_marks(cr, panel, s, o);
    if (o.scale_bar) draw_caption(cr, panel, o);
  }
}

void check_options(const PreviewScene& s, const ImageOptions& o) {
  if (o.width_px < 16 || o.height_px < 16 || o.width_px > 20000 || o.height_px > 20000) {
    throw InputError("size = " + std::to_string(o.width_px) + "x" + std::to_string(o.height_px) +
                     ": must be in [16, 20000] pixels each way");
  }
  const int n = static_cast<int>(s.layer_z_mm.size());
  if (o.layer >= n || o.layer < -1) {
    throw InputError("layer = " + std::to_string(o.layer) + ": must be in [0, " + std::to_string(n - 1) +
                     "] (the file has " + std::to_string(n) + " layers)");
  }
}

cairo_status_t append(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

}  // namespace

std::vector<PreviewMark> marks_from(const CheckReport& report) {
  std::vector<PreviewMark> marks;
  for (const auto& l : report.layers) {
    for (const auto& c : l.crossings) marks.push_back({l.layer, c.at_mm, true});
    for (const auto& c : l.touches) marks.push_back({l.layer, c.at_mm, false});
  }
  return marks;
}

std::string render_png(const PreviewScene& scene, const ImageOptions& o) {
  check_options(scene, o);
  std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> surface(
      cairo_image_surface_create(CAIRO_FORMAT_RGB24, o.width_px, o.height_px), &cairo_surface_destroy);
  std::unique_ptr<cairo_t, decltype(&cairo_destroy)> cr(cairo_create(surface.get()), &cairo_destroy);
  draw(cr.get(), scene, o);
  cairo_surface_flush(surface.get());
  std::string png;
  cairo_surface_write_to_png_stream(surface.get(), &append, &png);
  return png;
}

std::string render_svg(const PreviewScene& scene, const ImageOptions& o) {
  check_options(scene, o);
  std::string svg;
  {
    std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> surface(
        cairo_svg_surface_create_for_stream(&append, &svg, o.width_px, o.height_px), &cairo_surface_destroy);
    std::unique_ptr<cairo_t, decltype(&cairo_destroy)> cr(cairo_create(surface.get()), &cairo_destroy);
    draw(cr.get(), scene, o);
    cr.reset();
    cairo_surface_finish(surface.get());
  }
  return svg;
}

}  // namespace strand::post
