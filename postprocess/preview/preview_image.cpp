// Cairo drawing shared by the PNG and SVG previews.
#include "postprocess/preview/preview_image.h"

#include <cairo-svg.h>
#include <cairo.h>

#include <Eigen/Geometry>  // cross products for substrate shading

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>

#include "postprocess/preview/preview_depth.h"
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
  // Isometric: x to the lower right, y to the upper right, z up (screen y grows down); seen
  // from (1, -1, 1), so a part is drawn as it is, not mirrored.
  return {(p.x() + p.y()) * kCos30, (p.x() - p.y()) * 0.5 - p.z()};
}

// Distance towards the viewer in mm (larger is nearer), for drawing 3D scenes back to front.
double nearness(const Vec3& p, PreviewView view) {
  return view == PreviewView::Top ? p.z() : (p.x() - p.y() + p.z()) / std::sqrt(3.0);
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

// The substrate's colour, light so the paths read on it; shaded by how squarely a triangle
// faces the viewer.
Rgb substrate_shade(const Vec3& normal, PreviewView view) {
  const Vec3 towards = view == PreviewView::Top ? Vec3::UnitZ() : Vec3(1, -1, 1).normalized();
  const double facing = std::abs(normal.normalized().dot(towards));
  const double v = 0.80 + 0.14 * facing;
  return {v, v, v + 0.03};
}

void set_path_style(cairo_t* cr, const PreviewPath& p, const PreviewScene& s,
                    const ImageOptions& o, double bead_px) {
  if (p.travel) {
    cairo_set_source_rgba(cr, 0.45, 0.45, 0.45, 0.8);
    cairo_set_line_width(cr, 0.75);
    return;
  }
  set_colour(cr, o.colouring == PreviewColouring::Layer
                     ? layer_colour(p.layer, static_cast<int>(s.layer_z_mm.size()))
                     : deposit_key(s, p).colour);
  cairo_set_line_width(cr, bead_px);
}

// The substrate as a light shaded solid: faces turned away first, then faces towards the
// viewer, each group far to near (right for a convex substrate, and an open end still shows
// the inside); each triangle filled and stroked thinly in its colour so no seam shows.
// Returns the triangles as a depth map for hiding what lies behind them.
DepthMap draw_substrate(cairo_t* cr, const Panel& panel, const PreviewScene& s, int width_px,
                        int height_px) {
  const auto& m = s.substrate;
  std::vector<std::array<Vec2, 3>> screen;
  std::vector<std::array<double, 3>> near;
  std::vector<std::pair<double, std::size_t>> order;  // (facing, nearness) key, triangle
  std::vector<Vec3> normals;
  for (std::size_t i = 0; i < m.triangles.size(); ++i) {
    Triangle t;
    for (int k = 0; k < 3; ++k) t[k] = m.vertices_mm[static_cast<std::size_t>(m.triangles[i][k])];
    screen.push_back({panel.at(t[0]), panel.at(t[1]), panel.at(t[2])});
    near.push_back({nearness(t[0], panel.view), nearness(t[1], panel.view),
                    nearness(t[2], panel.view)});
    normals.push_back((t[1] - t[0]).cross(t[2] - t[0]));
    const Vec2 e1 = screen[i][1] - screen[i][0], e2 = screen[i][2] - screen[i][0];
    const bool towards = e1.x() * e2.y() - e1.y() * e2.x() < 0;  // ccw on screen (y down)
    order.emplace_back((towards ? 1e12 : 0.0) + near[i][0] + near[i][1] + near[i][2], i);
  }
  std::stable_sort(order.begin(), order.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_width(cr, 0.6);
  for (const auto& [key, i] : order) {
    set_colour(cr, substrate_shade(normals[i], panel.view));
    for (const Vec2& q : screen[i]) cairo_line_to(cr, q.x(), q.y());
    cairo_close_path(cr);
    cairo_fill_preserve(cr);
    cairo_stroke(cr);
  }
  return depth_map(std::move(screen), std::move(near), width_px, height_px);
}

// Each visible path in order, as one polyline. In a 3D scene (a substrate, or paths off
// their layer's plane) the substrate comes first and a path is cut into runs of the
// segments whose middle is not behind it, so the far side of a sleeve is not drawn; later
// layers lie outside earlier ones, so path order needs no depth sort.
void draw_paths(cairo_t* cr, const Panel& panel, const PreviewScene& s, const ImageOptions& o,
                int width_px, int height_px) {
  DepthMap depth = is_3d(s) ? draw_substrate(cr, panel, s, width_px, height_px) : DepthMap{};
  if (!s.substrate_hides_paths) depth = DepthMap{};
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  const double bead_px = std::max(1.0, (s.bead_width_mm > 0 ? s.bead_width_mm : 0.4) * panel.scale);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  for (const auto& p : s.paths) {
    if (!visible(p, o)) continue;
    set_path_style(cr, p, s, o, bead_px);
    bool open = false;
    for (std::size_t i = 0; i + 1 < p.points_mm.size(); ++i) {
      const Vec3 mid = 0.5 * (p.points_mm[i] + p.points_mm[i + 1]);
      if (behind(depth, panel.at(mid), nearness(mid, panel.view))) {
        open = false;
        continue;
      }
      const Vec2 a = panel.at(p.points_mm[i]), b = panel.at(p.points_mm[i + 1]);
      if (!open) cairo_move_to(cr, a.x(), a.y());
      cairo_line_to(cr, b.x(), b.y());
      open = true;
    }
    cairo_stroke(cr);
  }
}

// One row of swatches at the top left: the features drawn (or the first and last layer's
// colour), travel when drawn, and the substrate.
void draw_legend(cairo_t* cr, const PreviewScene& s, const ImageOptions& o) {
  std::vector<std::pair<std::string, Rgb>> keys;
  const int layers = static_cast<int>(s.layer_z_mm.size());
  if (o.colouring == PreviewColouring::Layer) {
    const int first = o.layer >= 0 ? o.layer : 0, last = o.layer >= 0 ? o.layer : layers - 1;
    keys.push_back({"layer " + std::to_string(first), layer_colour(first, layers)});
    if (last != first) {
      keys.push_back({"layer " + std::to_string(last), layer_colour(last, layers)});
    }
  } else {
    for (const PreviewKey& k : deposit_keys(s, [&o](const PreviewPath& p) { return visible(p, o); }))
      keys.push_back({k.name, k.colour});
  }
  if (o.travel) keys.push_back({"travel", {0.45, 0.45, 0.45}});
  if (!s.substrate.triangles.empty()) keys.push_back({"substrate", {0.80, 0.80, 0.83}});
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, 12.0);
  double x = kMarginPx;
  for (const auto& [name, colour] : keys) {
    set_colour(cr, colour);
    cairo_rectangle(cr, x, 7, 11, 11);
    cairo_fill(cr);
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    cairo_move_to(cr, x + 15, 17);
    cairo_show_text(cr, name.c_str());
    cairo_text_extents_t ext;
    cairo_text_extents(cr, name.c_str(), &ext);
    x += 15 + ext.x_advance + 12;
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
    cairo_save(cr);
    cairo_rectangle(cr, panel.x0, panel.y0, panel.w, panel.h);
    cairo_clip(cr);
    draw_paths(cr, panel, s, o, o.width_px, o.height_px);
    if (!o.marks.empty()) draw_marks(cr, panel, s, o);
    if (o.scale_bar) draw_caption(cr, panel, o);
    cairo_restore(cr);
  }
  if (o.scale_bar) draw_legend(cr, s, o);
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
