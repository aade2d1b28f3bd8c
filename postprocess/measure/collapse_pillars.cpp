// Pillars found in a side photo: backdrop, ink, the opened blocks, their order and corners.
#include "postprocess/measure/collapse_pillars.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "postprocess/measure/measure_setup.h"
#include "slicer/input_error.h"

namespace strand::post::measure {

namespace {

// A pillar's block fills at least this share of its rotated bounding rectangle.
constexpr double kLeastFill = 0.75;
// The blocks' centres along the row may miss the report's pillars by this share of a
// pillar's width (rms, after the best 1-D perspective fit).
constexpr double kSpacingSlack = 0.25;

std::string percent(double share) {
  return std::to_string(static_cast<long>(std::lround(std::clamp(share, -1e6, 1e6) * 100))) + " %";
}

// The backdrop's brightness: the photo with every ink feature narrower than `kernel_px`
// closed over (dark ink) or opened away (light ink), on a coarse copy, smoothed.
cv::Mat background(const cv::Mat& gray, double kernel_px, bool dark) {
  const double f = std::min(1.0, 24.0 / std::max(kernel_px, 1.0));
  cv::Mat small;
  cv::resize(gray, small, cv::Size(std::max(1, static_cast<int>(std::lround(gray.cols * f))),
                                   std::max(1, static_cast<int>(std::lround(gray.rows * f)))),
             0, 0, cv::INTER_AREA);
  const int k = std::max(3, static_cast<int>(std::lround(kernel_px * f))) | 1;
  cv::morphologyEx(small, small, dark ? cv::MORPH_CLOSE : cv::MORPH_OPEN,
                   cv::getStructuringElement(cv::MORPH_ELLIPSE, {k, k}));
  cv::GaussianBlur(small, small, {0, 0}, k / 6.0);
  cv::Mat bg;
  cv::resize(small, bg, gray.size(), 0, 0, cv::INTER_LINEAR);
  return cv::max(bg, 1.0);
}

// Ink at half its own level. Otsu parts ink from backdrop; a bed between the two in
// brightness can fall on the ink's side, so Otsu again parts what it called ink, and the
// stronger part's median (away from its edges) is the level. Pure ink parts into its noise's
// halves, whose upper median is the level all the same. The mask's edges sit at half the
// level, as the view's do.
cv::Mat ink_mask(const cv::Mat& s, double& level) {
  cv::Mat s8, m, inner;
  s.convertTo(s8, CV_8U, 127.5);
  const double t1 = cv::threshold(s8, m, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU);
  cv::erode(m, inner, cv::Mat(), {-1, -1}, 2);
  std::vector<uchar> v;
  const int stride = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(s.total()) / 2e5)));
  for (int y = 0; y < s.rows; y += stride) {
    for (int x = 0; x < s.cols; x += stride) {
      if (inner.at<uchar>(y, x)) v.push_back(s8.at<uchar>(y, x));
    }
  }
  level = 0.0;
  if (!v.empty()) {
    cv::Mat part;
    const double t2 = cv::threshold(cv::Mat(v, false), part, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU);
    std::vector<double> upper;
    for (uchar u : v) {
      if (u > std::max(t1, t2)) upper.push_back(u / 127.5);
    }
    level = median(upper);
  }
  cv::Mat mask = s > level / 2;
  cv::morphologyEx(mask, mask, cv::MORPH_OPEN, cv::Mat());
  return mask;
}

// Blocks thicker than `share` of the thickest ink: the mask opened with a disc of that
// radius (through two distance transforms), so the thin filament falls away and the pillars
// stay, their corners rounded by the disc.
std::vector<PillarBlock> blocks(const cv::Mat& mask, double share, double& rho) {
  cv::Mat dt, far;
  cv::distanceTransform(mask, dt, cv::DIST_L2, 3);
  double r_max = 0.0;
  cv::minMaxLoc(dt, nullptr, &r_max);
  rho = std::max(1.0, share * r_max);
  const cv::Mat core = dt >= rho;
  cv::distanceTransform(~core, far, cv::DIST_L2, 3);
  const cv::Mat opened = (far <= rho) & mask;
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(opened, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
  std::vector<std::pair<double, PillarBlock>> found;
  double largest = 0.0;
  for (auto& c : contours) {
    if (c.size() < 8) continue;
    const cv::RotatedRect r = cv::minAreaRect(c);
    const double area = cv::contourArea(c);
    if (area < kLeastFill * r.size.area()) continue;
    found.push_back({area, {r, std::move(c)}});
    largest = std::max(largest, area);
  }
  std::vector<PillarBlock> out;
  for (auto& [area, b] : found) {
    if (area >= 0.25 * largest) out.push_back(std::move(b));
  }
  return out;
}

// The rms miss of a 1-D perspective fit t = (a X + b) / (e X + 1) (affine below 4 points);
// infinite when the fit shrinks one end of the row to less than half the other's scale (no
// side view foreshortens a row so much; the pole within the row is the extreme of that).
double row_fit_rms(const std::vector<double>& x, const std::vector<double>& t) {
  const int n = static_cast<int>(x.size());
  const bool projective = n >= 4;
  cv::Mat a(n, projective ? 3 : 2, CV_64F), y(n, 1, CV_64F), p;
  for (int i = 0; i < n; ++i) {
    a.at<double>(i, 0) = x[i];
    a.at<double>(i, 1) = 1.0;
    if (projective) a.at<double>(i, 2) = -x[i] * t[i];
    y.at<double>(i) = t[i];
  }
  cv::solve(a, y, p, cv::DECOMP_SVD);
  const double e = projective ? p.at<double>(2) : 0.0;
  const double ends = (e * x.front() + 1.0) / (e * x.back() + 1.0);  // the scales' ratio is its square
  if (!(ends * ends >= 0.5 && ends * ends <= 2.0)) return HUGE_VAL;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double fit = (p.at<double>(0) * x[i] + p.at<double>(1)) / (e * x[i] + 1.0);
    sum += (fit - t[i]) * (fit - t[i]);
  }
  return std::sqrt(sum / n);
}

// One search for the pillars, with ink darker (or lighter) than the backdrop.
struct Search {
  FoundPillars found;
  int rank = 0;  // 0 low contrast, 1 wrong count, 2 off level or wrongly spaced, 3 found
  double spread = HUGE_VAL;  // of the blocks' areas (with the first share): pillars are alike
  std::string problem;
};

// (largest - smallest) / median of the blocks' areas. With the wrong polarity the gaps between
// the pillars are the blocks, and they differ as the gaps do.
double spread(const std::vector<PillarBlock>& blocks) {
  std::vector<double> areas;
  for (const auto& b : blocks) areas.push_back(b.rect.size.area());
  if (areas.empty()) return HUGE_VAL;
  const auto [lo, hi] = std::minmax_element(areas.begin(), areas.end());
  return (*hi - *lo) / std::max(1.0, median(areas));
}

// Orders the blocks along the row and matches their spacing to the report's, either way
// round; false (with the problem said) when the row is off level or spaced otherwise.
bool order_row(std::vector<PillarBlock> blocks, const PillarRow& row, Search& s) {
  std::vector<cv::Point2f> centres;
  for (const auto& b : blocks) centres.push_back(b.rect.center);
  cv::Vec4f line;
  cv::fitLine(centres, line, cv::DIST_L2, 0, 0.01, 0.01);
  cv::Point2d d(line[0], line[1]);
  if (d.x < 0) d = -d;
  if (std::abs(d.y) > std::abs(d.x)) {
    s.problem = "the row of pillars runs more than 45 deg off level; turn the photo upright";
    return false;
  }
  std::sort(blocks.begin(), blocks.end(),
            [&](const auto& a, const auto& b) { return d.dot(a.rect.center) < d.dot(b.rect.center); });
  std::vector<double> t, widths;
  for (const auto& b : blocks) {
    t.push_back(d.dot(b.rect.center));
    cv::Point2f p[4];
    b.rect.points(p);
    double lo = 1e300, hi = -1e300;
    for (const auto& q : p) {
      lo = std::min(lo, d.dot(q));
      hi = std::max(hi, d.dot(q));
    }
    widths.push_back(hi - lo);
  }
  const std::size_t n = blocks.size();
  std::vector<double> forward, backward;
  for (std::size_t i = 0; i < n; ++i) {
    forward.push_back(row.left_mm[i] + row.side_mm / 2);
    backward.push_back(row.left_mm[n - 1 - i] + row.side_mm / 2);
  }
  const double width = std::max(1.0, median(widths));
  const double miss_forward = row_fit_rms(forward, t) / width, miss_backward = row_fit_rms(backward, t) / width;
  const bool mirrored = miss_backward < 0.5 * miss_forward;
  const double miss = mirrored ? miss_backward : miss_forward;
  if (miss > kSpacingSlack) {
    s.problem = "the " + std::to_string(n) + " blocks found are not spaced as the report's pillars (off by " +
                percent(std::min(miss_forward, miss_backward)) + " of a pillar's width either way round); is it this print?";
    return false;
  }
  s.found.blocks = std::move(blocks);
  s.found.along = d;
  s.found.mirrored = mirrored;
  return true;
}

Search search(const cv::Mat& gray, const PillarRow& row, bool dark, double kernel_px) {
  Search s;
  FoundPillars& f = s.found;
  f.dark_ink = dark;
  f.background = background(gray, kernel_px, dark);
  const cv::Mat mask = ink_mask(ink_strength(gray, f.background, dark), f.contrast);
  if (!(f.contrast >= kLeastInkContrast)) {
    s.problem = "ink contrast " + percent(f.contrast) + " of the backdrop, below " + percent(kLeastInkContrast) +
                ": the photo is blurred, badly exposed or not of this print";
    return s;
  }
  const std::size_t want = row.left_mm.size();
  std::size_t first_count = 0;  // with the first share, the one told
  s.rank = 1;
  for (double share : {0.5, 0.35, 0.65}) {
    std::vector<PillarBlock> found = blocks(mask, share, f.rounding_px);
    if (share == 0.5) {
      first_count = found.size();
      s.spread = spread(found);
    }
    if (found.size() != want) continue;
    s.rank = 2;
    if (order_row(std::move(found), row, s)) {
      s.rank = 3;
      s.problem.clear();
      return s;
    }
  }
  if (s.rank == 1) {
    s.problem = "found " + std::to_string(first_count) + " blocks standing on the bed where the report has " +
                std::to_string(want) + " pillars; photograph the whole row from the side, level with the pillar tops, "
                "in focus";
  }
  return s;
}

// A line through fitted points: a point on it and its direction.
struct Line {
  cv::Point2d at, dir;
};

cv::Point2d crossing(const Line& a, const Line& b) {
  const double det = a.dir.x * b.dir.y - a.dir.y * b.dir.x;
  if (std::abs(det) < 1e-12) return a.at;
  const cv::Point2d d = b.at - a.at;
  return a.at + a.dir * ((d.x * b.dir.y - d.y * b.dir.x) / det);
}

}  // namespace

cv::Mat ink_strength(const cv::Mat& gray, const cv::Mat& background, bool dark_ink) {
  cv::Mat s = gray / background;
  s = dark_ink ? 1.0 - s : s - 1.0;
  return cv::min(cv::max(s, 0.0), 2.0);
}

FoundPillars find_pillars(const cv::Mat& gray, const PillarRow& row, const std::string& what) {
  // The background's kernel: 1.5 pillars wide if the row filled the photo's long side (it
  // cannot fill more), so pillars are taken out of the background and a wider bed is not.
  const double row_mm = row.left_mm.back() + row.side_mm - row.left_mm.front();
  const double long_px = std::max(gray.cols, gray.rows);
  const double kernel_px = std::clamp(1.5 * long_px * row.side_mm / row_mm, 9.0, std::max(9.0, long_px / 2));
  Search s = search(gray, row, true, kernel_px);
  if (s.rank < 3) {
    // Light ink told instead when it gets further, or as far with blocks more alike (with
    // too little contrast both, the higher contrast).
    Search light = search(gray, row, false, kernel_px);
    const bool alike = s.rank == 0 ? light.found.contrast > s.found.contrast : light.spread < s.spread;
    if (light.rank > s.rank || (light.rank == s.rank && alike)) s = std::move(light);
  }
  if (s.rank < 3) throw InputError(what + ": " + s.problem);
  return std::move(s.found);
}

std::array<cv::Point2d, 4> pillar_corners(const PillarBlock& block, const cv::Point2d& along, double rounding_px) {
  const cv::Point2d up(along.y, -along.x);  // photo y points down
  double u0 = 1e300, u1 = -1e300, v0 = 1e300, v1 = -1e300;
  for (const auto& p : block.outline) {
    u0 = std::min(u0, along.dot(p));
    u1 = std::max(u1, along.dot(p));
    v0 = std::min(v0, up.dot(p));
    v1 = std::max(v1, up.dot(p));
  }
  // Each side: the outline's points within a fifth of the block of it, clear of the corners.
  const double band_u = 0.2 * (u1 - u0), band_v = 0.2 * (v1 - v0), skip = 1.2 * rounding_px + 1;
  std::vector<cv::Point2f> side[4];  // bottom, top, left, right
  for (const auto& p : block.outline) {
    const double u = along.dot(p), v = up.dot(p);
    const bool mid_u = u > u0 + skip && u < u1 - skip, mid_v = v > v0 + skip && v < v1 - skip;
    if (mid_u && v < v0 + band_v) side[0].push_back(p);
    if (mid_u && v > v1 - band_v) side[1].push_back(p);
    if (mid_v && u < u0 + band_u) side[2].push_back(p);
    if (mid_v && u > u1 - band_u) side[3].push_back(p);
  }
  const cv::Point2d out[4] = {-up, up, -along, along};
  Line lines[4];
  for (int k = 0; k < 4; ++k) {
    if (side[k].size() < 3) {  // too few pixels for straight sides: the bounding box's side
      const double reach = k < 2 ? (v1 - v0) / 2 : (u1 - u0) / 2;
      const cv::Point2d centre = along * ((u0 + u1) / 2) + up * ((v0 + v1) / 2);
      lines[k] = {centre + out[k] * (reach + 0.5), k < 2 ? along : up};
      continue;
    }
    cv::Vec4f l;
    cv::fitLine(side[k], l, cv::DIST_HUBER, 0, 0.01, 0.01);
    lines[k] = {cv::Point2d(l[2], l[3]) + out[k] * 0.5, cv::Point2d(l[0], l[1])};
  }
  return {crossing(lines[0], lines[2]), crossing(lines[0], lines[3]), crossing(lines[1], lines[2]),
          crossing(lines[1], lines[3])};
}

}  // namespace strand::post::measure
