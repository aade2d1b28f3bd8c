// Pores from a rectified photo: a window per pore, the half-level outline, A, L and Pr.
#include "postprocess/measure/measure_pores.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "slicer/input_error.h"

namespace strand::post::measure {

namespace {

// Below this share of the bed's brightness the ink cannot be told from the bed reliably.
constexpr double kLeastContrast = 0.08;
// Finer grid the outline is traced on (bicubic), so its steps are a quarter pixel.
constexpr int kUpsample = 4;

struct Pore {
  int index = 0;
  cv::Point2d centre_mm;
  double side_mm = 0.0;
};

struct PoreResult {
  std::string status = "measured";  // or "filled", "open"
  double area_mm2 = 0.0, perimeter_mm = 0.0, pr = 0.0, contrast = 0.0;
  double blur_mm = 0.0;  // sigma of the blur its edges show
  std::vector<cv::Point2d> outline_px;  // in the rectified photo
};

double median_of(const cv::Mat& gray, const cv::Rect& box) {
  std::vector<double> v;
  const cv::Rect b = box & cv::Rect(0, 0, gray.cols, gray.rows);
  for (int y = b.y; y < b.y + b.height; ++y) {
    for (int x = b.x; x < b.x + b.width; ++x) v.push_back(gray.at<float>(y, x));
  }
  return median(v);
}

cv::Rect box_px(const Rectified& r, const cv::Point2d& c_mm, double half_mm) {
  const cv::Point2d a = r.to_px(c_mm.x - half_mm, c_mm.y + half_mm), b = r.to_px(c_mm.x + half_mm, c_mm.y - half_mm);
  return cv::Rect(cv::Point(static_cast<int>(std::floor(a.x)), static_cast<int>(std::floor(a.y))),
                  cv::Point(static_cast<int>(std::ceil(b.x)) + 1, static_cast<int>(std::ceil(b.y)) + 1));
}

// Moving average over +-k points of a closed outline: takes the staircase off the traced
// pixel path, which would otherwise lengthen every slanted or curved stretch.
std::vector<cv::Point2d> smoothed(const std::vector<cv::Point>& c, int k) {
  const int n = static_cast<int>(c.size());
  std::vector<cv::Point2d> out(c.size());
  for (int i = 0; i < n; ++i) {
    cv::Point2d s(0, 0);
    for (int j = -k; j <= k; ++j) s += cv::Point2d(c[static_cast<std::size_t>(((i + j) % n + n) % n)]);
    out[static_cast<std::size_t>(i)] = s * (1.0 / (2 * k + 1));
  }
  return out;
}

// The half-level outline of a sharp corner blurred by a Gaussian of sigma is shorter than the
// corner by 0.842 sigma: a corner rounded to kBlurRadius x sigma (computed from the outline
// Phi(x / sigma) Phi(y / sigma) = 1/2).
constexpr double kBlurRadius = 1.96;

// Blur as the measured pore's edges show it: the distance between the 75 % and 25 % levels
// across the middle third of each side, averaged (1.349 sigma for a Gaussian). `share` is the
// bed's share (1 open, 0 ink) on the fine grid; `c` the centre, `half` half the window (px).
double blur_sigma_px(const cv::Mat& share, const cv::Point& c, int band) {
  std::vector<double> widths;
  for (int side = 0; side < 4; ++side) {
    const bool along_x = side < 2;
    const int dir = side % 2 == 0 ? 1 : -1;
    std::vector<double> profile;
    for (int t = 0;; ++t) {
      double sum = 0;
      int n = 0;
      for (int b = -band; b <= band; ++b) {
        const int x = along_x ? c.x + dir * t : c.x + b, y = along_x ? c.y + b : c.y + dir * t;
        if (x < 0 || y < 0 || x >= share.cols || y >= share.rows) continue;
        sum += share.at<double>(y, x);
        ++n;
      }
      if (n == 0) break;
      profile.push_back(sum / n);
    }
    auto crossing = [&](double level) {
      for (std::size_t i = 1; i < profile.size(); ++i) {
        if (profile[i - 1] >= level && profile[i] < level) return (i - 1) + (profile[i - 1] - level) / (profile[i - 1] - profile[i]);
      }
      return -1.0;
    };
    const double a = crossing(0.75), b = crossing(0.25);
    if (a >= 0 && b > a) widths.push_back(b - a);
  }
  return widths.empty() ? 0.0 : median(widths) / 1.349;
}

// The outline taken as a square with rounded corners (side s, radius rho: A = s^2 - k rho^2,
// L = 4 s - 2 k rho, k = 4 - pi); the blur's share of the rounding given back to the corners.
struct Corners {
  double perimeter_mm = 0.0, area_mm2 = 0.0;
};
Corners blur_corrected(double l_iso, double a_iso, double sigma_mm) {
  const double k = 4 - CV_PI;
  // rho of the outline: k (k/4 - 1) rho^2 + (k L / 4) rho + (L^2/16 - A) = 0, the root in [0, s/2].
  const double qa = k * (k / 4 - 1), qb = k * l_iso / 4, qc = l_iso * l_iso / 16 - a_iso;
  const double disc = qb * qb - 4 * qa * qc;
  double rho = 0.0;
  if (qc < 0 && disc >= 0) rho = std::max(0.0, (-qb + std::sqrt(disc)) / (2 * qa));
  const double blur = kBlurRadius * sigma_mm;
  const double rho0 = std::sqrt(std::max(0.0, rho * rho - blur * blur));
  return {l_iso + 2 * k * (rho - rho0), a_iso + k * (rho * rho - rho0 * rho0)};
}

PoreResult measure_one(const Rectified& r, const Pore& p, double pitch_mm, double nozzle_mm) {
  PoreResult out;
  const cv::Rect window = box_px(r, p.centre_mm, pitch_mm / 2) & cv::Rect(0, 0, r.gray.cols, r.gray.rows);
  const double bed = median_of(r.gray, box_px(r, p.centre_mm, p.side_mm / 6));
  std::vector<double> crossings;
  for (int sx : {-1, 1}) {
    for (int sy : {-1, 1}) {
      const cv::Point2d c = p.centre_mm + cv::Point2d(sx, sy) * (pitch_mm / 2);
      crossings.push_back(median_of(r.gray, box_px(r, c, nozzle_mm / 4)));
    }
  }
  const double ink = median(crossings);
  out.contrast = (r.dark_ink ? bed - ink : ink - bed) / std::max(1.0, bed);
  if (out.contrast < kLeastContrast) {
    out.status = "filled";
    return out;
  }
  cv::Mat fine;
  cv::resize(r.gray(window), fine, {}, kUpsample, kUpsample, cv::INTER_CUBIC);
  cv::Mat open;
  const double level = (bed + ink) / 2;
  if (r.dark_ink) cv::compare(fine, level, open, cv::CMP_GT);
  else cv::compare(fine, level, open, cv::CMP_LT);
  cv::Mat labels;
  cv::connectedComponents(open, labels, 4, CV_32S);
  const cv::Point2d centre = r.to_px(p.centre_mm.x, p.centre_mm.y);
  const int cx = static_cast<int>((centre.x - window.x) * kUpsample), cy = static_cast<int>((centre.y - window.y) * kUpsample);
  const int label = labels.at<int>(std::clamp(cy, 0, labels.rows - 1), std::clamp(cx, 0, labels.cols - 1));
  if (label == 0) {
    out.status = "filled";
    return out;
  }
  cv::Mat region = labels == label;
  const bool edge = cv::countNonZero(region.row(0)) || cv::countNonZero(region.row(region.rows - 1)) ||
                    cv::countNonZero(region.col(0)) || cv::countNonZero(region.col(region.cols - 1));
  if (edge) {
    out.status = "open";
    return out;
  }
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(region, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
  const auto& c = *std::max_element(contours.begin(), contours.end(),
                                    [](const auto& a, const auto& b) { return a.size() < b.size(); });
  const std::vector<cv::Point2d> s = smoothed(c, kUpsample);
  std::vector<cv::Point2f> poly;
  for (const auto& q : s) poly.emplace_back(static_cast<float>(q.x), static_cast<float>(q.y));
  // The traced path runs through the centres of the region's edge pixels, half a fine pixel
  // inside its edge: grown by that half pixel (Steiner: A + L d + pi d^2, L + 2 pi d).
  const double d = 0.5;
  const double l_fine = cv::arcLength(poly, true), a_fine = std::abs(cv::contourArea(poly));
  const double scale = kUpsample * r.px_per_mm;
  const double l_iso = (l_fine + 2 * CV_PI * d) / scale;
  const double a_iso = (a_fine + l_fine * d + CV_PI * d * d) / (scale * scale);
  cv::Mat share;
  fine.convertTo(share, CV_64F, 1.0 / (bed - ink), -ink / (bed - ink));
  const double sigma_mm = blur_sigma_px(share, {cx, cy}, static_cast<int>(p.side_mm / 6 * scale)) / scale;
  const Corners fixed = blur_corrected(l_iso, a_iso, sigma_mm);
  out.blur_mm = sigma_mm;
  out.perimeter_mm = fixed.perimeter_mm;
  out.area_mm2 = fixed.area_mm2;
  out.pr = out.perimeter_mm * out.perimeter_mm / (16 * out.area_mm2);
  for (const auto& q : s) out.outline_px.emplace_back(window.x + (q.x + 0.5) / kUpsample - 0.5, window.y + (q.y + 0.5) / kUpsample - 0.5);
  return out;
}

cv::Scalar colour_for(double pr) {
  if (pr >= 0.95) return {40, 180, 40};   // square: green
  if (pr >= 0.85) return {0, 150, 255};   // rounded: orange
  return {40, 40, 220};                   // round or irregular: red
}

}  // namespace

Measured measure_pores(const cv::Mat& photo, const nlohmann::json& report, const std::string& what) {
  const nlohmann::json derived = derived_of_test(report, "pore", "pore-test", what);
  const std::vector<Fiducial> marks = fiducials_of(derived, what);
  std::vector<Pore> pores;
  double pitch = 0.0, nozzle = 0.0;
  try {
    for (const auto& p : derived.at("pores")) {
      pores.push_back({p.at("index").get<int>(), {p.at("centre_mm")[0], p.at("centre_mm")[1]}, p.at("side_mm")});
    }
    pitch = derived.at("pitch_mm").get<double>();
    nozzle = derived.at("nozzle_mm").get<double>();
  } catch (const nlohmann::json::exception&) {
    throw InputError(what + ": the job report lacks derived pores, pitch_mm or nozzle_mm");
  }
  if (pores.empty() || pitch <= 0 || nozzle <= 0) {
    throw InputError(what + ": the job report needs pores, pitch_mm > 0 and nozzle_mm > 0");
  }
  double smallest = pitch;
  for (const auto& p : pores) smallest = std::min(smallest, p.side_mm);
  // About 48 pixels along the smallest pore's side.
  const Rectified r = rectified_photo(photo, marks, std::clamp(48.0 / smallest, 8.0, 80.0), nozzle, what);

  std::vector<PoreResult> results;
  std::vector<double> contrasts;
  for (const auto& p : pores) {
    results.push_back(measure_one(r, p, pitch, nozzle));
    contrasts.push_back(results.back().contrast);
  }
  const double contrast = median(contrasts);
  if (contrast < kLeastContrast) {
    throw InputError(what + ": ink contrast " + std::to_string(static_cast<int>(std::lround(contrast * 100))) +
                     " % of the bed, below " + std::to_string(static_cast<int>(kLeastContrast * 100)) +
                     " %: the photo is blurred, badly exposed or not of this print");
  }

  Measured out;
  out.overlay = r.color.clone();
  nlohmann::json jp = nlohmann::json::array();
  std::ostringstream text;
  text << std::fixed;
  double sum = 0.0;
  int measured = 0;
  for (std::size_t i = 0; i < pores.size(); ++i) {
    const Pore& p = pores[i];
    const PoreResult& m = results[i];
    const bool ok = m.status == "measured";
    jp.push_back({{"index", p.index},
                  {"centre_mm", {p.centre_mm.x, p.centre_mm.y}},
                  {"intended_side_mm", p.side_mm},
                  {"status", m.status},
                  {"area_mm2", ok ? nlohmann::json(round_to(m.area_mm2, 4)) : nlohmann::json()},
                  {"perimeter_mm", ok ? nlohmann::json(round_to(m.perimeter_mm, 4)) : nlohmann::json()},
                  {"pr", ok ? nlohmann::json(round_to(m.pr, 4)) : nlohmann::json()},
                  {"blur_mm", ok ? nlohmann::json(round_to(m.blur_mm, 4)) : nlohmann::json()}});
    text << "  pore " << std::setw(2) << p.index;
    if (ok) {
      sum += m.pr;
      ++measured;
      text << "  area " << std::setprecision(3) << m.area_mm2 << " mm2 (intended " << p.side_mm * p.side_mm
           << ")  perimeter " << m.perimeter_mm << " mm  Pr " << m.pr << "\n";
      std::vector<cv::Point> poly;
      for (const auto& q : m.outline_px) poly.emplace_back(cv::Point(static_cast<int>(std::lround(q.x)), static_cast<int>(std::lround(q.y))));
      cv::polylines(out.overlay, std::vector<std::vector<cv::Point>>{poly}, true, colour_for(m.pr), 2, cv::LINE_AA);
    } else {
      text << "  " << m.status << (m.status == "open" ? " (joined to its neighbour or the outside)" : " (no open area)") << "\n";
    }
    const double h = p.side_mm / 2;
    cv::rectangle(out.overlay, r.to_px(p.centre_mm.x - h, p.centre_mm.y + h), r.to_px(p.centre_mm.x + h, p.centre_mm.y - h),
                  {255, 80, 0}, 1, cv::LINE_AA);
    std::ostringstream label;
    label << std::fixed << std::setprecision(2) << (ok ? m.pr : 0.0);
    cv::putText(out.overlay, ok ? label.str() : m.status, r.to_px(p.centre_mm.x - h * 0.8, p.centre_mm.y),
                cv::FONT_HERSHEY_SIMPLEX, 0.35, {255, 80, 0}, 1, cv::LINE_AA);
  }
  for (const auto& f : marks) {
    cv::circle(out.overlay, r.to_px(f.x_mm, f.y_mm), static_cast<int>(f.size_mm * r.px_per_mm * 0.75), {200, 0, 200}, 2,
               cv::LINE_AA);
  }
  cv::putText(out.overlay, "blue: intended pores; outline: measured (green Pr >= 0.95, orange >= 0.85, red below)", {6, 16},
              cv::FONT_HERSHEY_SIMPLEX, 0.45, {0, 0, 0}, 1, cv::LINE_AA);
  const nlohmann::json mean = measured > 0 ? nlohmann::json(round_to(sum / measured, 4)) : nlohmann::json();
  text << "  mean Pr " << (measured > 0 ? std::to_string(round_to(sum / measured, 3)).substr(0, 5) : std::string("-"))
       << " over " << measured << " of " << pores.size() << " pores\n";
  out.items = std::to_string(pores.size()) + " pores";
  out.details = text.str();
  out.json = {{"test", "pore"},
              {"nozzle_mm", nozzle},
              {"ink", r.dark_ink ? "darker than the bed" : "lighter than the bed"},
              {"contrast", round_to(contrast, 3)},
              {"px_per_mm", round_to(r.px_per_mm, 3)},
              {"mean_pr", mean},
              {"pores_measured", measured},
              {"pores", jp}};
  return out;
}

}  // namespace strand::post::measure
