// A photo of a printed ink test, made from the generated test's own path: beads of known
// width, then what a camera does to them (perspective tilt and a scale the measurer does not
// know, blur, uneven light, noise). Shared by the measure and CLI tests.
#pragma once

#include <cmath>
#include <functional>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>
#include <stb_image_write.h>
#include <string>
#include <vector>

#include "slicer/toolpath.h"

namespace strand::testing {

struct PhotoSetup {
  double render_px_per_mm = 24.0;  // the "bed" is drawn this finely, then photographed
  double tilt_deg = 8.0;           // camera tilt: one side of the frame this much further away
  double scale = 0.55;             // photo pixels per rendered pixel (the unknown scale)
  double turn_deg = 3.0;           // camera turned about its axis
  double blur_px = 1.3;
  double noise = 4.0;              // grey levels, standard deviation
  double light_from = 0.65;        // light falls off across the frame from 1.15 to this
  bool dark_ink = true;
  bool draw_marks = true;
};

// Truth: the width of each line by its index.
using WidthOf = std::function<double(const nlohmann::json& line)>;

inline double segment_distance(const cv::Point2d& p, const cv::Point2d& a, const cv::Point2d& b) {
  const cv::Point2d d = b - a;
  const double t = std::clamp(((p - a).dot(d)) / d.dot(d), 0.0, 1.0);
  const cv::Point2d q = a + d * t - p;
  return std::hypot(q.x, q.y);
}

struct Bead {
  cv::Point2d a, b;
  double w = 0.0;
};

// The bed as drawn before the camera: pixel (0, 0) is bed point (bx, by), y down.
struct Canvas {
  cv::Mat img;  // CV_32F grey levels
  double bx = 0.0, by = 0.0, ppm = 24.0;
  float ink = 70.0f, back = 215.0f;
  bool dark = true;
  cv::Point2d mm(int x, int y) const { return {bx + (x + 0.5) / ppm, by - (y + 0.5) / ppm}; }
  // Lays ink of area coverage `cover(p_mm)` (0..1) over the pixels of the box [lo, hi] (mm).
  template <class Cover>
  void paint(const cv::Point2d& lo, const cv::Point2d& hi, const Cover& cover) {
    const int c0 = std::max(0, static_cast<int>((lo.x - bx) * ppm)), c1 = std::min(img.cols - 1, static_cast<int>((hi.x - bx) * ppm) + 1);
    const int r0 = std::max(0, static_cast<int>((by - hi.y) * ppm)), r1 = std::min(img.rows - 1, static_cast<int>((by - lo.y) * ppm) + 1);
    for (int y = r0; y <= r1; ++y) {
      float* row = img.ptr<float>(y);
      for (int x = c0; x <= c1; ++x) {
        const float v = static_cast<float>(back + (ink - back) * std::clamp(cover(mm(x, y)), 0.0, 1.0));
        row[x] = dark ? std::min(row[x], v) : std::max(row[x], v);
      }
    }
  }
  void bead(const Bead& g) {
    const double r = g.w / 2 + 2 / ppm;
    paint({std::min(g.a.x, g.b.x) - r, std::min(g.a.y, g.b.y) - r}, {std::max(g.a.x, g.b.x) + r, std::max(g.a.y, g.b.y) + r},
          [&](const cv::Point2d& p) { return 0.5 + (g.w / 2 - segment_distance(p, g.a, g.b)) * ppm; });
  }
};

// A bed spanning the report's fiducials plus a margin, with the marks drawn (nozzle wide).
inline Canvas bed_canvas(const nlohmann::json& derived, const PhotoSetup& s) {
  const double nozzle = derived.at("nozzle_mm");
  double x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9;
  for (const auto& f : derived.at("fiducials")) {
    const double cx = f["x_mm"], cy = f["y_mm"], h = f["size_mm"].get<double>() / 2;
    x0 = std::min(x0, cx - h); x1 = std::max(x1, cx + h); y0 = std::min(y0, cy - h); y1 = std::max(y1, cy + h);
  }
  const double margin = 6.0;
  Canvas c;
  c.ppm = s.render_px_per_mm;
  c.bx = x0 - margin;
  c.by = y1 + margin;
  c.dark = s.dark_ink;
  c.ink = s.dark_ink ? 70.0f : 250.0f;
  c.back = s.dark_ink ? 215.0f : 90.0f;
  c.img = cv::Mat(static_cast<int>((y1 - y0 + 2 * margin) * c.ppm), static_cast<int>((x1 - x0 + 2 * margin) * c.ppm), CV_32F,
                  cv::Scalar(c.back));
  if (!s.draw_marks) return c;
  for (const auto& f : derived.at("fiducials")) {
    const double cx = f["x_mm"], cy = f["y_mm"], h = f["size_mm"].get<double>() / 2;
    const cv::Point2d q[4] = {{cx - h, cy - h}, {cx + h, cy - h}, {cx + h, cy + h}, {cx - h, cy + h}};
    for (int k = 0; k < 4; ++k) c.bead({q[k], q[(k + 1) % 4], nozzle});
  }
  return c;
}

// Every stroke of every layer but the marks (bed_canvas draws those) as beads `width_mm` wide.
inline void draw_toolpath(Canvas& c, const slicer::Toolpath& t, double width_mm) {
  for (const auto& l : t.layers) {
    for (const auto& s : l.strokes) {
      cv::Point2d a(s.start_mm.x(), s.start_mm.y());
      for (const auto& seg : s.segments) {
        const cv::Point2d b(seg.end_mm.x(), seg.end_mm.y());
        if (seg.feature != slicer::Feature::Frame) c.bead({a, b, width_mm});
        a = b;
      }
    }
  }
}

// The camera: turned, tilted (a trapezoid) and scaled, then blurred, lit unevenly and noisy.
inline cv::Mat photograph(const Canvas& c, const PhotoSetup& s) {
  cv::Mat canvas = c.img.clone();
  const double w = canvas.cols, h = canvas.rows, k = std::tan(s.tilt_deg * CV_PI / 180) * 0.5;
  std::vector<cv::Point2f> src = {{0, 0}, {float(w), 0}, {float(w), float(h)}, {0, float(h)}};
  std::vector<cv::Point2f> dst;
  const double t = s.turn_deg * CV_PI / 180;
  const cv::Point2d corners[4] = {{-w / 2 * (1 - k), -h / 2}, {w / 2 * (1 - k), -h / 2}, {w / 2 * (1 + k), h / 2}, {-w / 2 * (1 + k), h / 2}};
  for (const auto& q0 : corners) {
    const cv::Point2d q(q0.x * std::cos(t) - q0.y * std::sin(t), q0.x * std::sin(t) + q0.y * std::cos(t));
    dst.emplace_back(static_cast<float>((q.x * 0.92 + w * 0.6) * s.scale), static_cast<float>((q.y * 0.92 + h * 0.6) * s.scale));
  }
  cv::Mat photo;
  const cv::Size size(static_cast<int>(w * 1.2 * s.scale), static_cast<int>(h * 1.2 * s.scale));
  cv::GaussianBlur(canvas, canvas, {0, 0}, 0.5 / s.scale);  // no aliasing in the resampling
  cv::warpPerspective(canvas, photo, cv::getPerspectiveTransform(src, dst), size, cv::INTER_LINEAR, cv::BORDER_CONSTANT,
                      cv::Scalar(c.back));
  cv::GaussianBlur(photo, photo, {0, 0}, s.blur_px);
  for (int y = 0; y < photo.rows; ++y) {
    float* row = photo.ptr<float>(y);
    for (int x = 0; x < photo.cols; ++x) {
      const double u = (x + 0.5 * y) / (photo.cols + 0.5 * photo.rows);
      row[x] = static_cast<float>(row[x] * (1.15 + (s.light_from - 1.15) * u));
    }
  }
  cv::Mat noise(photo.size(), CV_32F);
  cv::RNG rng(12345);
  rng.fill(noise, cv::RNG::NORMAL, 0.0, s.noise);
  photo += noise;
  cv::Mat gray8, bgr;
  photo.convertTo(gray8, CV_8U);
  cv::cvtColor(gray8, bgr, cv::COLOR_GRAY2BGR);
  return bgr;
}

// A line matrix: the report's lines (width from `width_of`) and square marks (nozzle wide).
inline cv::Mat synthetic_photo(const nlohmann::json& derived, const WidthOf& width_of, const PhotoSetup& s = {}) {
  Canvas c = bed_canvas(derived, s);
  for (const auto& l : derived.at("lines")) {
    c.bead({{l["start_mm"][0], l["start_mm"][1]}, {l["end_mm"][0], l["end_mm"][1]}, width_of(l)});
  }
  return photograph(c, s);
}

// A photo as JPEG bytes (the samples in samples/ink/ are made so).
inline std::string encode_jpeg(const cv::Mat& bgr, int quality = 90) {
  cv::Mat rgb;
  cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
  std::string out;
  const auto append = [](void* context, void* bytes, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(bytes), static_cast<std::size_t>(size));
  };
  stbi_write_jpg_to_func(append, &out, rgb.cols, rgb.rows, 3, rgb.data, quality);
  return out;
}

// The power law the tests print with: width = 0.62 * flow^0.6 * (speed / 300)^-0.4 mm.
inline double law_width(const nlohmann::json& l) {
  return 0.62 * std::pow(l["flow"].get<double>(), 0.6) * std::pow(l["speed_mm_min"].get<double>() / 300.0, -0.4);
}

}  // namespace strand::testing
