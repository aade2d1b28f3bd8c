// A side photo of a printed collapse test, made from the generated test's own report: the
// pillars standing on a bed, one filament across their tops that sags into each gap by a
// chosen depth (a parabola, held above the bed: a depth past the pillars' height lays the
// filament on the bed), the bed's marks as low strips, then the camera of synthetic_photo.h
// (turned, a trapezoid of perspective, an unknown scale, blur, uneven light, noise).
#pragma once

#include <stb_image.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tests/postprocess/measure/synthetic_photo.h"

namespace strand::testing {

// Sag of a gap: the depth of its parabola (mm), or kMissing for no filament over it.
inline constexpr double kMissing = -1.0;

struct SideSetup {
  PhotoSetup camera = side_camera();
  double filament_mm = 0.0;   // the filament's thickness; 0: the report's layer height
  bool from_back = false;     // the row seen from behind: mirrored
  static PhotoSetup side_camera() {
    PhotoSetup s;
    s.render_px_per_mm = 24.0;
    s.turn_deg = 7.0;
    s.tilt_deg = 6.0;
    s.scale = 0.6;
    s.blur_px = 1.2;
    return s;
  }
};

// The gaps and pillars a report lays out, x ascending.
struct SideLayout {
  std::vector<double> x0, x1;  // each gap's faces
  double side = 0.0, pillar_h = 0.0, top = 0.0, nozzle = 0.0, layer_h = 0.0;
  explicit SideLayout(const nlohmann::json& d)
      : side(d.at("pillar_mm")), pillar_h(d.at("pillar_height_mm")), top(d.at("filament_z_mm")),
        nozzle(d.at("nozzle_mm")), layer_h(d.at("layer_height_mm")) {
    for (const auto& g : d.at("gaps")) {
      x0.push_back(g.at("start_mm")[0]);
      x1.push_back(g.at("end_mm")[0]);
    }
  }
  double first() const { return x0.front() - side; }
  double last() const { return x1.back() + side; }
};

// The filament's underside at x: the pillar height, less the sag in a gap (at least 0).
inline double underside(const SideLayout& l, const std::vector<double>& depth, double x) {
  for (std::size_t k = 0; k < l.x0.size(); ++k) {
    if (x > l.x0[k] && x < l.x1[k]) {
      const double u = (x - l.x0[k]) / (l.x1[k] - l.x0[k]);
      return depth[k] == kMissing ? NAN : std::max(0.0, l.pillar_h - depth[k] * 4 * u * (1 - u));
    }
  }
  return l.pillar_h;
}

// The truth: Cf (%) of gap k, the mean underside over the pillar height.
inline double truth_area_factor(const SideLayout& l, const std::vector<double>& depth, std::size_t k) {
  if (depth[k] == kMissing) return 0.0;
  double sum = 0.0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) sum += underside(l, depth, l.x0[k] + (l.x1[k] - l.x0[k]) * (i + 0.5) / n);
  return 100.0 * sum / (n * l.pillar_h);
}

// The upright plane drawn: pixel (0, 0) is plane point (bx, by) with by the top (z up).
inline Canvas side_canvas(const nlohmann::json& d, const std::vector<double>& depth, const SideSetup& s) {
  const SideLayout l(d);
  const double nozzle = l.nozzle;
  // The row and its marks with 14 mm all round, 40 mm high round the row's middle: room for
  // the camera to turn without its frame leaving the scene (side_photo crops to the frame).
  double marks_x = 0.0;
  for (const auto& f : d.at("fiducials")) {
    marks_x = std::max(marks_x, std::abs(f["x_mm"].get<double>()) + f["size_mm"].get<double>() / 2);
  }
  const double half = std::max(marks_x, (l.last() - l.first()) / 2) + 14.0, middle = (l.first() + l.last()) / 2;
  Canvas c;
  c.ppm = s.camera.render_px_per_mm;
  c.bx = middle - half;
  c.by = l.top / 2 + 20.0;
  c.dark = s.camera.dark_ink;
  c.ink = c.dark ? 70.0f : 250.0f;
  c.back = c.dark ? 215.0f : 90.0f;
  c.img = cv::Mat(static_cast<int>(40.0 * c.ppm), static_cast<int>(2 * half * c.ppm), CV_32F, cv::Scalar(c.back));
  // The bed: a surface a little darker (lighter) than the backdrop, shading towards the front.
  for (int y = static_cast<int>(c.by * c.ppm); y < c.img.rows; ++y) {
    const double depth_mm = y / c.ppm - c.by;
    const float level = c.dark ? static_cast<float>(178 - 3 * depth_mm) : static_cast<float>(112 + 2 * depth_mm);
    c.img.row(y).setTo(level);
  }
  const auto box = [&](double x0, double x1, double z0, double z1) {
    c.paint({x0, z0}, {x1, z1}, [&](const cv::Point2d& p) {
      return 0.5 + std::min({p.x - x0, x1 - p.x, p.y - z0, z1 - p.y}) * c.ppm;
    });
  };
  for (std::size_t k = 0; k <= l.x0.size(); ++k) {
    const double left = k == 0 ? l.first() : l.x1[k - 1];
    box(left, left + l.side, 0.0, l.pillar_h);
  }
  for (const auto& f : d.at("fiducials")) {
    const double cx = f["x_mm"], h = f["size_mm"].get<double>() / 2;
    box(cx - h, cx + h, 0.0, l.layer_h);
  }
  // The filament, s.filament_mm thick across its own slope, nozzle/2 short of the outer faces.
  const double f0 = l.first() + nozzle / 2, f1 = l.last() - nozzle / 2;
  const double t = s.filament_mm > 0 ? s.filament_mm : l.layer_h;
  c.paint({f0, -0.1}, {f1, l.top + 0.2}, [&](const cv::Point2d& p) {
    const double zu = underside(l, depth, p.x);
    if (std::isnan(zu)) return 0.0;
    const double e = 1e-3, slope = (underside(l, depth, p.x + e) - underside(l, depth, p.x - e)) / (2 * e);
    const double stretch = std::isnan(slope) ? 1.0 : std::sqrt(1 + slope * slope);
    // The top held at the filament's top over the pillars: no lip where it turns down.
    const double inside = std::min({p.y - zu, std::min(zu + t * stretch, l.pillar_h + t) - p.y}) / stretch;
    return 0.5 + std::min(inside, std::min(p.x - f0, f1 - p.x)) * c.ppm;
  });
  if (s.from_back) cv::flip(c.img, c.img, 1);
  return c;
}

// The camera's frame: the middle three quarters of the photographed scene, which the scene
// fills whatever the camera's turn (up to 10 deg) and perspective.
inline cv::Mat side_photo(const nlohmann::json& derived, const std::vector<double>& depth, const SideSetup& s = {}) {
  const Canvas c = side_canvas(derived, depth, s);
  const cv::Mat shot = photograph(c, s.camera);
  const double w = 0.75 * 0.92 * c.img.cols * s.camera.scale, h = 0.75 * 0.92 * c.img.rows * s.camera.scale;
  const cv::Point2d centre(0.6 * c.img.cols * s.camera.scale, 0.6 * c.img.rows * s.camera.scale);
  return shot(cv::Rect(static_cast<int>(centre.x - w / 2), static_cast<int>(centre.y - h / 2), static_cast<int>(w),
                       static_cast<int>(h)))
      .clone();
}

// The photo through a JPEG and back, as a camera would save it.
inline cv::Mat through_jpeg(const cv::Mat& bgr, int quality = 90) {
  const std::string bytes = encode_jpeg(bgr, quality);
  int w = 0, h = 0, n = 0;
  stbi_uc* rgb = stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()),
                                       static_cast<int>(bytes.size()), &w, &h, &n, 3);
  cv::Mat out;
  cv::cvtColor(cv::Mat(h, w, CV_8UC3, rgb), out, cv::COLOR_RGB2BGR);
  stbi_image_free(rgb);
  return out;
}

}  // namespace strand::testing
