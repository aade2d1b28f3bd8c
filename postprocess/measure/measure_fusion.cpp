// Fused lengths from a rectified photo: stations along each pair's mid-line.
#include "postprocess/measure/measure_fusion.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "slicer/input_error.h"

namespace strand::post::measure {

namespace {

constexpr int kStations = 80;
constexpr double kLeastContrast = 0.08;

struct Pair {
  int index = 0;
  double spacing_mm = 0.0;
  double left_x = 0.0, right_x = 0.0;
  cv::Point2d a, b;  // the measured zone along the mid-line, mm
};

// Ink contrast relative to the bed at (x, y): positive on ink.
double contrast_at(const Rectified& r, double x_mm, double y_mm, double bed) {
  const cv::Point2d p = r.to_px(x_mm, y_mm);
  const double g = sample(r.gray, p.x, p.y);
  return (r.dark_ink ? bed - g : g - bed) / std::max(1.0, bed);
}

}  // namespace

Measured measure_fusion(const cv::Mat& photo, const nlohmann::json& report, const std::string& what) {
  const nlohmann::json derived = derived_of_test(report, "fusion", "fusion-test", what);
  const std::vector<Fiducial> marks = fiducials_of(derived, what);
  std::vector<Pair> pairs;
  double nozzle = 0.0;
  try {
    for (const auto& s : derived.at("spacings")) {
      pairs.push_back({s.at("index").get<int>(), s.at("spacing_mm"), s.at("filaments_x_mm")[0], s.at("filaments_x_mm")[1],
                       {s.at("start_mm")[0], s.at("start_mm")[1]}, {s.at("end_mm")[0], s.at("end_mm")[1]}});
    }
    nozzle = derived.at("nozzle_mm").get<double>();
  } catch (const nlohmann::json::exception&) {
    throw InputError(what + ": the job report lacks derived spacings or nozzle_mm");
  }
  if (pairs.empty() || nozzle <= 0) throw InputError(what + ": the job report needs spacings and nozzle_mm > 0");
  const Rectified r = rectified_photo(photo, marks, std::clamp(14.0 / nozzle, 4.0, 50.0), nozzle, what);

  double x_min = 1e300, x_max = -1e300;
  for (const auto& p : pairs) {
    x_min = std::min(x_min, p.left_x);
    x_max = std::max(x_max, p.right_x);
  }
  const double beside = 4 * nozzle;
  // Per station height: the bed beside the meander on both sides, interpolated across.
  auto bed_at = [&](double x, double y) {
    const cv::Point2d l = r.to_px(x_min - beside, y), rr = r.to_px(x_max + beside, y);
    const double bl = sample(r.gray, l.x, l.y), br = sample(r.gray, rr.x, rr.y);
    return bl + (br - bl) * (x - (x_min - beside)) / (x_max - x_min + 2 * beside);
  };
  // Full contrast: on the filaments' centre lines of every pair.
  std::vector<double> on_ink;
  for (const auto& p : pairs) {
    for (int k = 0; k < kStations; ++k) {
      const double y = p.a.y + (p.b.y - p.a.y) * (k + 0.5) / kStations;
      for (double x : {p.left_x, p.right_x}) on_ink.push_back(contrast_at(r, x, y, bed_at(x, y)));
    }
  }
  const double full = median(on_ink);
  if (full < kLeastContrast) {
    throw InputError(what + ": ink contrast " + std::to_string(static_cast<int>(std::lround(full * 100))) + " % of the bed, below " +
                     std::to_string(static_cast<int>(kLeastContrast * 100)) +
                     " %: the photo is blurred, badly exposed or not of this print");
  }

  Measured out;
  out.overlay = r.color.clone();
  nlohmann::json js = nlohmann::json::array();
  std::ostringstream text;
  text << std::fixed;
  nlohmann::json closest_separate = nullptr;
  bool all_separate_so_far = true;
  const double step_mm = 1.0 / r.px_per_mm;
  for (const auto& p : pairs) {
    const double mid = (p.left_x + p.right_x) / 2, reach = (p.right_x - p.left_x) / 4;
    const double zone = std::abs(p.b.y - p.a.y);
    int fused = 0;
    for (int k = 0; k < kStations; ++k) {
      const double y = p.a.y + (p.b.y - p.a.y) * (k + 0.5) / kStations;
      double least = 1e300;
      for (double x = mid - reach; x <= mid + reach + 1e-12; x += std::min(step_mm, reach)) {
        least = std::min(least, contrast_at(r, x, y, bed_at(x, y)) / full);
      }
      const bool f = least > 0.5;
      fused += f;
      const cv::Point2d q = r.to_px(mid, y);
      cv::circle(out.overlay, q, 2, f ? cv::Scalar(40, 40, 220) : cv::Scalar(40, 180, 40), cv::FILLED, cv::LINE_AA);
    }
    const double share = static_cast<double>(fused) / kStations;
    const std::string cls = share >= kFusedShare ? "fused" : "separate";
    if (cls == "fused") all_separate_so_far = false;
    if (cls == "separate" && all_separate_so_far) closest_separate = p.spacing_mm;
    js.push_back({{"index", p.index},
                  {"spacing_mm", p.spacing_mm},
                  {"zone_length_mm", round_to(zone, 4)},
                  {"fused_length_mm", round_to(share * zone, 4)},
                  {"fused_share", round_to(share, 4)},
                  {"class", cls}});
    text << "  spacing " << std::setw(2) << p.index << "  " << std::setprecision(3) << p.spacing_mm << " mm  fused "
         << share * zone << " of " << zone << " mm  " << cls << "\n";
    cv::putText(out.overlay, cls == "fused" ? "F" : "S", r.to_px(mid - nozzle / 2, p.b.y + 2 * nozzle), cv::FONT_HERSHEY_SIMPLEX, 0.4,
                {255, 80, 0}, 1, cv::LINE_AA);
  }
  for (const auto& f : marks) {
    cv::circle(out.overlay, r.to_px(f.x_mm, f.y_mm), static_cast<int>(f.size_mm * r.px_per_mm * 0.75), {200, 0, 200}, 2,
               cv::LINE_AA);
  }
  cv::putText(out.overlay, "dots on each gap's mid-line: red fused, green separate", {6, 16}, cv::FONT_HERSHEY_SIMPLEX, 0.45,
              {0, 0, 0}, 1, cv::LINE_AA);
  out.items = std::to_string(pairs.size()) + " spacings";
  out.details = text.str();
  out.json = {{"test", "fusion"},
              {"nozzle_mm", nozzle},
              {"ink", r.dark_ink ? "darker than the bed" : "lighter than the bed"},
              {"contrast", round_to(full, 3)},
              {"px_per_mm", round_to(r.px_per_mm, 3)},
              {"closest_separate_spacing_mm", closest_separate},
              {"spacings", js}};
  return out;
}

}  // namespace strand::post::measure
