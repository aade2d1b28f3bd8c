// Line widths from a rectified photo: stations along each line, a contrast profile across.
#include "postprocess/measure/measure_lines.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "postprocess/measure/photo.h"
#include "slicer/input_error.h"

namespace strand::post::measure {

namespace {

constexpr int kStations = 60;
// Below this share of the bed's brightness the ink cannot be told from the bed reliably.
constexpr double kLeastContrast = 0.08;

struct Line {
  int index = 0;
  double speed = 0.0, flow = 0.0, width = 0.0;
  cv::Point2d a, b;  // mm
};

// One station's contrast profile across the line: (bed - ink) / bed, positive on ink.
struct Station {
  cv::Point2d centre_mm;
  double integral_mm = 0.0;  // contrast integrated across, mm
  double peak = 0.0;
};

Station station(const Rectified& r, const cv::Point2d& c_mm, const cv::Point2d& n, double half_mm) {
  const double step_mm = 1.0 / r.px_per_mm;
  const int half = static_cast<int>(std::ceil(half_mm / step_mm));
  const int inner = static_cast<int>(0.8 * half);
  std::vector<double> g(static_cast<std::size_t>(2 * half + 1));
  std::vector<double> outer;
  for (int k = -half; k <= half; ++k) {
    const cv::Point2d p = c_mm + n * (k * step_mm);
    const cv::Point2d px = r.to_px(p.x, p.y);
    g[static_cast<std::size_t>(k + half)] = sample(r.gray, px.x, px.y);
    if (std::abs(k) > inner) outer.push_back(g[static_cast<std::size_t>(k + half)]);
  }
  const double bed = std::max(1.0, median(outer));
  Station s;
  s.centre_mm = c_mm;
  double prev = 0.0, cur = 0.0;
  for (int k = -inner; k <= inner; ++k) {
    const double v = (r.dark_ink ? bed - g[static_cast<std::size_t>(k + half)] : g[static_cast<std::size_t>(k + half)] - bed) / bed;
    s.integral_mm += v * step_mm;
    const double next = k < inner ? (r.dark_ink ? bed - g[static_cast<std::size_t>(k + half + 1)]
                                                : g[static_cast<std::size_t>(k + half + 1)] - bed) / bed
                                  : v;
    cur = v;
    if (k > -inner) s.peak = std::max(s.peak, (prev + cur + next) / 3);
    prev = cur;
  }
  return s;
}

cv::Scalar colour_for(double ratio) {
  if (ratio < 0.9) return {40, 40, 220};   // narrower than intended: red
  if (ratio > 1.1) return {0, 150, 255};   // wider: orange
  return {40, 180, 40};                    // within 10 %: green
}

}  // namespace

LinesMeasured measure_lines(const cv::Mat& photo, const nlohmann::json& report, const std::string& what) {
  const nlohmann::json derived = derived_of_test(report, "lines", "line-matrix", what);
  const std::vector<Fiducial> marks = fiducials_of(derived, what);
  std::vector<Line> lines;
  double nozzle = 0.0, spacing = 0.0;
  try {
    for (const auto& l : derived.at("lines")) {
      lines.push_back({l.at("index").get<int>(), l.at("speed_mm_min"), l.at("flow"), l.at("width_mm"),
                       {l.at("start_mm")[0], l.at("start_mm")[1]}, {l.at("end_mm")[0], l.at("end_mm")[1]}});
    }
    nozzle = derived.at("nozzle_mm").get<double>();
    spacing = derived.at("spacing_mm").get<double>();
  } catch (const nlohmann::json::exception&) {
    throw InputError(what + ": the job report lacks derived lines, nozzle_mm or spacing_mm");
  }
  if (lines.empty() || nozzle <= 0 || spacing <= 0) {
    throw InputError(what + ": the job report needs lines, nozzle_mm > 0 and spacing_mm > 0");
  }

  // About 14 pixels across a nozzle-wide bead.
  const Rectified r = rectified_photo(photo, marks, std::clamp(14.0 / nozzle, 4.0, 50.0), spacing, what);

  std::vector<std::vector<Station>> stations(lines.size());
  std::vector<double> peaks;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const Line& l = lines[i];
    const cv::Point2d d = l.b - l.a;
    const double len = std::hypot(d.x, d.y);
    const cv::Point2d u = d / len, n(-u.y, u.x);
    for (int k = 0; k < kStations; ++k) {
      const double t = len * (0.1 + 0.8 * (k + 0.5) / kStations);
      stations[i].push_back(station(r, l.a + u * t, n, spacing / 2));
      peaks.push_back(stations[i].back().peak);
    }
  }
  // Full contrast: the wider beads reach it in their middle whatever the blur.
  const double level = percentile(peaks, 0.75);
  if (level < kLeastContrast) {
    throw InputError(what + ": ink contrast " + std::to_string(static_cast<int>(std::lround(level * 100))) +
                     " % of the bed, below " + std::to_string(static_cast<int>(kLeastContrast * 100)) +
                     " %: the photo is blurred, badly exposed or not of this print");
  }

  LinesMeasured out;
  out.overlay = r.color.clone();
  nlohmann::json jl = nlohmann::json::array();
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const Line& l = lines[i];
    std::vector<double> widths;
    for (const auto& s : stations[i]) {
      const double w = s.integral_mm / level;
      if (w > 0.3 * l.width) widths.push_back(w);
    }
    LineWidth m{l.index, l.speed, l.flow, l.width, median(widths), 0.0,
                static_cast<double>(widths.size()) / kStations};
    if (widths.size() > 1) {
      double mean = 0.0, var = 0.0;
      for (double w : widths) mean += w;
      mean /= static_cast<double>(widths.size());
      for (double w : widths) var += (w - mean) * (w - mean);
      m.width_cv = std::sqrt(var / static_cast<double>(widths.size() - 1)) / mean;
    }
    out.lines.push_back(m);
    jl.push_back({{"index", m.index},
                  {"speed_mm_min", m.speed_mm_per_min},
                  {"flow", m.flow},
                  {"intended_width_mm", round_to(m.intended_width_mm, 4)},
                  {"width_mm", round_to(m.width_mm, 4)},
                  {"width_cv", round_to(m.width_cv, 4)},
                  {"coverage", round_to(m.coverage, 3)}});

    // Overlay: the intended centre line, and every third station's measured width across it.
    cv::line(out.overlay, r.to_px(l.a.x, l.a.y), r.to_px(l.b.x, l.b.y), {255, 80, 0}, 1, cv::LINE_AA);
    const cv::Point2d d = (l.b - l.a) / std::hypot(l.b.x - l.a.x, l.b.y - l.a.y);
    const cv::Point2d n(-d.y, d.x);
    for (std::size_t k = 0; k < stations[i].size(); k += 3) {
      const auto& s = stations[i][k];
      const double w = s.integral_mm / level;
      if (w <= 0.3 * l.width) continue;
      cv::line(out.overlay, r.to_px(s.centre_mm.x + n.x * w / 2, s.centre_mm.y + n.y * w / 2),
               r.to_px(s.centre_mm.x - n.x * w / 2, s.centre_mm.y - n.y * w / 2), colour_for(w / l.width), 2,
               cv::LINE_AA);
    }
    const cv::Point2d left = l.a.x < l.b.x ? l.a : l.b;
    const cv::Point2d label = r.to_px(left.x, left.y + spacing * 0.3);
    cv::putText(out.overlay, std::to_string(l.index) + ": " + std::to_string(static_cast<int>(std::lround(m.width_mm * 1000))) + " um",
                label, cv::FONT_HERSHEY_SIMPLEX, 0.35, {255, 80, 0}, 1, cv::LINE_AA);
  }
  for (const auto& f : marks) {
    cv::circle(out.overlay, r.to_px(f.x_mm, f.y_mm), static_cast<int>(f.size_mm * r.px_per_mm * 0.75),
               {200, 0, 200}, 2, cv::LINE_AA);
  }
  cv::putText(out.overlay, "blue: intended lines; ticks: measured width (green within 10 %, red narrower, orange wider)",
              {6, 16}, cv::FONT_HERSHEY_SIMPLEX, 0.45, {0, 0, 0}, 1, cv::LINE_AA);

  out.json = {{"test", "lines"},
              {"nozzle_mm", nozzle},
              {"layer_height_mm", derived.value("layer_height_mm", 0.8 * nozzle)},
              {"ink", r.dark_ink ? "darker than the bed" : "lighter than the bed"},
              {"contrast", round_to(level, 3)},
              {"px_per_mm", round_to(r.px_per_mm, 3)},
              {"lines", jl}};
  return out;
}

Measured lines_measured(const LinesMeasured& m) {
  std::ostringstream out;
  out << std::fixed;
  for (const auto& l : m.lines) {
    out << "  line " << std::setw(2) << l.index << "  speed " << std::setprecision(0) << l.speed_mm_per_min
        << " mm/min  flow " << std::setprecision(2) << l.flow << "  width " << std::setprecision(3) << l.width_mm
        << " mm (intended " << l.intended_width_mm << ")  cv " << std::setprecision(1) << 100 * l.width_cv
        << " %  coverage " << std::setprecision(0) << 100 * l.coverage << " %\n";
  }
  return {std::to_string(m.lines.size()) + " lines", m.json, m.overlay, out.str()};
}

}  // namespace strand::post::measure
