// The plane mapping fitted to the pillars' corners, the view warped and its ink share, and
// the checks on it.
#include "postprocess/measure/collapse_side_view.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "postprocess/measure/measure_setup.h"
#include "postprocess/measure/plane_homography.h"
#include "slicer/input_error.h"

namespace strand::post::measure {

namespace {

// Pillars are looked for in the photo scaled down to at most this many pixels; the view is
// warped from the photo itself.
constexpr double kWorkPixels = 4e6;
// The corners may miss the fitted plane mapping by this share of a pillar's side (rms).
constexpr double kCornerSlack = 0.08;
// The side faces' 20-80 % edge may be this many nozzles wide; wider, and the filament (about
// a nozzle thick) blurs into the gap below it.
constexpr double kMostEdgeNozzles = 0.75;
// The view: at most this many pixels, and each side at most kMostViewSide (OpenCV's remap).
constexpr double kMostViewPixels = 20e6;
constexpr double kMostViewSide = 30000;

std::string percent(double share) {
  return std::to_string(static_cast<long>(std::lround(std::clamp(share, -1e6, 1e6) * 100))) + " %";
}

std::string fixed(double v, int digits) {
  std::ostringstream o;
  o << std::fixed << std::setprecision(digits) << v;
  return o.str();
}

// The photo scaled by `k` (at most 1: never enlarged), at least a pixel each way.
cv::Mat scaled(const cv::Mat& photo, double k) {
  if (!(k < 1.0)) return photo;
  cv::Mat out;
  cv::resize(photo, out, cv::Size(std::max(1, static_cast<int>(photo.cols * k)), std::max(1, static_cast<int>(photo.rows * k))),
             0, 0, cv::INTER_AREA);
  return out;
}

// Pixel of a scaled copy -> pixel of the photo (centres aligned, as cv::resize has them).
cv::Matx33d from_scaled(const cv::Mat& copy, const cv::Mat& photo) {
  const double kx = static_cast<double>(copy.cols) / photo.cols, ky = static_cast<double>(copy.rows) / photo.rows;
  return {1 / kx, 0, 0.5 / kx - 0.5, 0, 1 / ky, 0.5 / ky - 0.5, 0, 0, 1};
}

// The four corners of each pillar in the photo, matched to their plane points (x, z) in mm.
void corners(const FoundPillars& f, const PillarRow& row, const cv::Matx33d& to_photo, std::vector<cv::Point2d>& photo_px,
             std::vector<cv::Point2d>& plane_mm) {
  const std::size_t n = f.blocks.size();
  for (std::size_t i = 0; i < n; ++i) {
    const double left = row.left_mm[f.mirrored ? n - 1 - i : i];
    const double photo_left = f.mirrored ? left + row.side_mm : left, photo_right = f.mirrored ? left : left + row.side_mm;
    const auto c = pillar_corners(f.blocks[i], f.along, f.rounding_px);
    const cv::Point2d plane[4] = {{photo_left, 0.0}, {photo_right, 0.0}, {photo_left, row.top_mm}, {photo_right, row.top_mm}};
    for (int k = 0; k < 4; ++k) {
      photo_px.push_back(apply(to_photo, c[k]));
      plane_mm.push_back(plane[k]);
    }
  }
}

// The median 20-80 % width of the pillars' side faces in the view, across mid-height rows.
double edge_width_mm(const SideView& v, const PillarRow& row, double margin_mm) {
  std::vector<double> widths;
  const std::size_t n = row.left_mm.size();
  const double step = 1.0 / v.px_per_mm;
  for (std::size_t k = 0; k < n; ++k) {
    for (int side = -1; side <= 1; side += 2) {
      const double face = side < 0 ? row.left_mm[k] : row.left_mm[k] + row.side_mm;
      double room = margin_mm;
      if (side < 0 && k > 0) room = row.left_mm[k] - row.left_mm[k - 1] - row.side_mm;
      if (side > 0 && k + 1 < n) room = row.left_mm[k + 1] - row.left_mm[k] - row.side_mm;
      const double reach = std::min(0.45 * row.side_mm, 0.45 * room);
      for (int j = 0; j < 8; ++j) {
        const double z = row.top_mm * (0.2 + 0.05 * j);
        double x80 = NAN, x20 = NAN;
        for (double t = -reach; t <= reach; t += step) {
          const cv::Point2d p = v.to_px(face + side * t, z);
          const double ink = sample(v.ink, p.x, p.y);
          if (std::isnan(x80) && ink < 0.8) x80 = t;
          if (ink < 0.2) {
            x20 = t;
            break;
          }
        }
        if (!std::isnan(x80) && !std::isnan(x20)) widths.push_back(x20 - x80);
      }
    }
  }
  return widths.empty() ? 0.0 : median(widths);
}

// The view's ink share: the strength over the pillars' own level, inside their middles.
void ink_share(SideView& v, const cv::Mat& gray, const cv::Mat& bg, const PillarRow& row) {
  const cv::Mat s = ink_strength(gray, bg, v.dark_ink);
  std::vector<double> inside;
  for (double left : row.left_mm) {
    const cv::Point2d a = v.to_px(left + 0.25 * row.side_mm, 0.75 * row.top_mm);
    const cv::Point2d b = v.to_px(left + 0.75 * row.side_mm, 0.2 * row.top_mm);
    for (int y = std::max(0, static_cast<int>(a.y)); y <= std::min(s.rows - 1, static_cast<int>(b.y)); ++y) {
      for (int x = std::max(0, static_cast<int>(a.x)); x <= std::min(s.cols - 1, static_cast<int>(b.x)); ++x) {
        inside.push_back(s.at<float>(y, x));
      }
    }
  }
  v.contrast = median(inside);
  v.ink = s / std::max(v.contrast, 1e-3);
}

// The plane mapping fitted to the corners, robust to a face that ink hides: a filament that
// collapsed along a pillar's face widens the pillar there. The face (its two corners) that
// misses the fit most along x is left out while it misses by 4 x the faces' median and at
// least 2 % of a pillar's side, up to a third of the faces.
struct Fit {
  cv::Matx33d h;
  double rms_mm = 0.0;  // over the corners kept
};

Fit robust_fit(const std::vector<cv::Point2d>& photo_px, const std::vector<cv::Point2d>& plane_mm, double side_mm) {
  const std::size_t faces = photo_px.size() / 2;  // corners 4k, 4k+2 and 4k+1, 4k+3
  const auto corners_of = [](std::size_t f) {
    const std::size_t base = 4 * (f / 2) + f % 2;
    return std::pair{base, base + 2};
  };
  std::vector<bool> kept(faces, true);
  Fit fit;
  for (std::size_t dropped = 0;; ++dropped) {
    std::vector<cv::Point2d> a, b;
    for (std::size_t f = 0; f < faces; ++f) {
      if (!kept[f]) continue;
      for (std::size_t i : {corners_of(f).first, corners_of(f).second}) {
        a.push_back(photo_px[i]);
        b.push_back(plane_mm[i]);
      }
    }
    fit.h = fit_homography(a, b);
    double sum = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) {
      const cv::Point2d d = apply(fit.h, a[i]) - b[i];
      sum += d.dot(d);
    }
    fit.rms_mm = std::sqrt(sum / static_cast<double>(a.size()));
    std::vector<double> miss(faces, 0.0), kept_miss;
    for (std::size_t f = 0; f < faces; ++f) {
      for (std::size_t i : {corners_of(f).first, corners_of(f).second}) miss[f] += std::abs((apply(fit.h, photo_px[i]) - plane_mm[i]).x) / 2;
      if (kept[f]) kept_miss.push_back(miss[f]);
    }
    std::size_t worst = faces;
    for (std::size_t f = 0; f < faces; ++f) {
      if (kept[f] && (worst == faces || miss[f] > miss[worst])) worst = f;
    }
    if (3 * (dropped + 1) > faces || miss[worst] < std::max(4 * median(kept_miss), 0.02 * side_mm)) return fit;
    kept[worst] = false;
  }
}

// The filament leaves every pillar at its top, so beside the faces there is ink at the top of
// the silhouette; a photo upside down has it at the bottom. The mean ink share in the top and
// bottom sixths, a tenth of a millimetre out from each face into the gaps.
bool upside_down(const SideView& v, const PillarRow& row) {
  double top = 0.0, bottom = 0.0;
  int samples = 0;
  for (std::size_t k = 0; k + 1 < row.left_mm.size(); ++k) {
    const double x0 = row.left_mm[k] + row.side_mm, x1 = row.left_mm[k + 1];
    const double out = std::min(0.1, (x1 - x0) / 4);
    for (double x : {x0 + out, x1 - out}) {
      for (int j = 0; j < 8; ++j) {
        const double dz = row.top_mm / 6 * (j + 0.5) / 8;
        const cv::Point2d t = v.to_px(x, row.top_mm - dz), b = v.to_px(x, dz);
        top += sample(v.ink, t.x, t.y);
        bottom += sample(v.ink, b.x, b.y);
        ++samples;
      }
    }
  }
  return bottom / samples > top / samples + 0.25;
}

// Photo pixel -> view pixel, through the plane (mm).
cv::Matx33d to_view(const SideView& v, const cv::Matx33d& photo_to_plane) {
  return cv::Matx33d(v.px_per_mm, 0, -v.x_min_mm * v.px_per_mm, 0, -v.px_per_mm, v.z_max_mm * v.px_per_mm, 0, 0, 1) *
         photo_to_plane;
}

// The view of the row plus the margin, in colour, warped from a copy of the photo of at most
// 1.5 photo pixels per view pixel (no aliasing from a finer photo).
SideView warped_view(const cv::Mat& photo, double photo_px_per_mm, const cv::Matx33d& photo_to_plane, const PillarRow& row,
                     double px_per_mm, double margin_mm) {
  SideView v;
  const double x0 = row.left_mm.front() - margin_mm, x1 = row.left_mm.back() + row.side_mm + margin_mm;
  const double z0 = -margin_mm, z1 = row.top_mm + margin_mm;
  v.px_per_mm = std::min({px_per_mm, std::sqrt(kMostViewPixels / ((x1 - x0) * (z1 - z0))), kMostViewSide / (x1 - x0),
                          kMostViewSide / (z1 - z0)});
  v.x_min_mm = x0;
  v.z_max_mm = z1;
  const cv::Size size(static_cast<int>(std::ceil((x1 - x0) * v.px_per_mm)), static_cast<int>(std::ceil((z1 - z0) * v.px_per_mm)));
  const cv::Mat source = scaled(photo, 1.5 * v.px_per_mm / std::max(photo_px_per_mm, 1e-9));
  cv::warpPerspective(source, v.color, cv::Mat(to_view(v, photo_to_plane) * from_scaled(source, photo)), size,
                      cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  return v;
}

// A photo from above shows the bed's four marks (a side view cannot): refused as such.
void refuse_view_from_above(const cv::Mat& work, const PillarRow& row, const std::string& what) {
  try {
    find_marks(work, row.marks, what);
  } catch (const InputError&) {
    return;
  }
  throw InputError(what + ": a view from above (the bed's 4 fiducial marks are seen); the collapse test is "
                   "measured from the side: photograph the row of pillars level with their tops");
}

}  // namespace

SideView rectified_side_view(const cv::Mat& photo, const PillarRow& row, double px_per_mm, double margin_mm,
                             const std::string& what) {
  if (photo.empty() || row.left_mm.size() < 2 || !(row.side_mm > 0) || !(row.top_mm > 0)) {
    throw InputError(what + ": no photo or no pillars to look for");
  }
  const cv::Mat work = scaled(photo, std::sqrt(kWorkPixels / static_cast<double>(photo.total())));
  if (row.marks.size() == 4) refuse_view_from_above(work, row, what);
  cv::Mat gray;
  cv::cvtColor(work, gray, cv::COLOR_BGR2GRAY);
  gray.convertTo(gray, CV_32F);
  const FoundPillars f = find_pillars(gray, row, what);

  std::vector<cv::Point2d> photo_px, plane_mm;
  const cv::Matx33d work_to_photo = from_scaled(work, photo);
  corners(f, row, work_to_photo, photo_px, plane_mm);
  const Fit fit = robust_fit(photo_px, plane_mm, row.side_mm);
  if (!(fit.rms_mm <= kCornerSlack * row.side_mm)) {
    throw InputError(what + ": the pillars' corners do not fit one upright plane (rms " + fixed(fit.rms_mm, 2) +
                     " mm); photograph the row square-on from the side, level with the pillar tops");
  }
  double bottoms_px = 0.0;
  for (std::size_t i = 1; i < photo_px.size(); i += 4) bottoms_px += cv::norm(photo_px[i] - photo_px[i - 1]);
  const double photo_px_per_mm = bottoms_px / (row.side_mm * static_cast<double>(row.left_mm.size()));

  SideView v = warped_view(photo, photo_px_per_mm, fit.h, row, px_per_mm, margin_mm);
  v.dark_ink = f.dark_ink;
  v.mirrored = f.mirrored;
  v.fit_rms_mm = fit.rms_mm;
  cv::Mat view_gray, view_bg;
  cv::cvtColor(v.color, view_gray, cv::COLOR_BGR2GRAY);
  view_gray.convertTo(view_gray, CV_32F);
  cv::warpPerspective(f.background, view_bg, cv::Mat(to_view(v, fit.h) * work_to_photo), v.color.size(), cv::INTER_LINEAR,
                      cv::BORDER_REPLICATE);
  ink_share(v, view_gray, view_bg, row);
  if (!(v.contrast >= kLeastInkContrast)) {
    throw InputError(what + ": ink contrast " + percent(v.contrast) + " of the backdrop on the pillars, below " +
                     percent(kLeastInkContrast) + ": the photo is blurred, badly exposed or not of this print");
  }
  if (upside_down(v, row)) {
    throw InputError(what + ": the filament runs along the pillars' feet: the photo is upside down; turn it upright");
  }
  v.edge_mm = edge_width_mm(v, row, margin_mm);
  if (v.edge_mm > kMostEdgeNozzles * row.nozzle_mm) {
    throw InputError(what + ": blurred: the pillars' edges are " + fixed(v.edge_mm, 2) + " mm wide, more than " +
                     fixed(kMostEdgeNozzles * row.nozzle_mm, 2) + " mm (0.75 x nozzle); refocus on the filament");
  }
  return v;
}

}  // namespace strand::post::measure
