// Reading a photo safely, finding its marks and rectifying it onto the bed plane.
#include "postprocess/measure/photo.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <stb_image.h>
#include <stb_image_write.h>

#include "slicer/file_io.h"
#include "slicer/input_error.h"

namespace strand::post::measure {

namespace {

unsigned be16(const std::string& b, std::size_t at) {
  return (static_cast<unsigned char>(b[at]) << 8) | static_cast<unsigned char>(b[at + 1]);
}
unsigned long be32(const std::string& b, std::size_t at) {
  return (static_cast<unsigned long>(be16(b, at)) << 16) | be16(b, at + 2);
}

// The frame size from a JPEG's first start-of-frame marker; {0, 0} if none is found.
cv::Size jpeg_size(const std::string& b) {
  std::size_t at = 2;
  while (at + 4 <= b.size()) {
    if (static_cast<unsigned char>(b[at]) != 0xFF) return {};
    const unsigned marker = static_cast<unsigned char>(b[at + 1]);
    if (marker == 0xFF) { ++at; continue; }  // fill byte
    if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD7)) { at += 2; continue; }
    const unsigned length = be16(b, at + 2);
    const bool sof = marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
    if (sof) {
      if (at + 9 > b.size()) return {};
      return {static_cast<int>(be16(b, at + 7)), static_cast<int>(be16(b, at + 5))};
    }
    if (length < 2) return {};
    at += 2 + length;
  }
  return {};
}

double angle_about(const cv::Point2d& p, const cv::Point2d& c) { return std::atan2(p.y - c.y, p.x - c.x); }

double wrapped(double a) {
  while (a > std::numbers::pi) a -= 2 * std::numbers::pi;
  while (a < -std::numbers::pi) a += 2 * std::numbers::pi;
  return a;
}

struct Candidate {
  cv::Point2d centre;
  double area = 0.0;
};

// Rings: an outer outline that is a convex quadrilateral with one large quadrilateral hole.
std::vector<Candidate> ring_candidates(const cv::Mat& gray8, bool dark) {
  const int side = std::min(gray8.cols, gray8.rows);
  const int block = std::max(15, side / 8) | 1;
  cv::Mat bin;
  cv::adaptiveThreshold(gray8, bin, 255, cv::ADAPTIVE_THRESH_MEAN_C,
                        dark ? cv::THRESH_BINARY_INV : cv::THRESH_BINARY, block, dark ? 12 : -12);
  std::vector<std::vector<cv::Point>> contours;
  std::vector<cv::Vec4i> tree;
  cv::findContours(bin, contours, tree, cv::RETR_CCOMP, cv::CHAIN_APPROX_SIMPLE);
  auto quad = [&](const std::vector<cv::Point>& c) {
    std::vector<cv::Point> approx;
    cv::approxPolyDP(c, approx, 0.06 * cv::arcLength(c, true), true);
    return approx.size() == 4 && cv::isContourConvex(approx);
  };
  auto centroid = [](const std::vector<cv::Point>& c) {
    const cv::Moments m = cv::moments(c);
    return cv::Point2d(m.m10 / m.m00, m.m01 / m.m00);
  };
  std::vector<Candidate> out;
  for (std::size_t i = 0; i < contours.size(); ++i) {
    if (tree[i][3] >= 0 || tree[i][2] < 0) continue;  // outer outlines with a hole only
    const double area = cv::contourArea(contours[i]);
    if (area < 64 || !quad(contours[i])) continue;
    int hole = -1;
    double hole_area = 0.0;
    for (int c = tree[i][2]; c >= 0; c = tree[c][0]) {
      const double a = cv::contourArea(contours[c]);
      if (a > hole_area) { hole_area = a; hole = c; }
    }
    if (hole < 0 || hole_area < 0.1 * area || hole_area > 0.85 * area || !quad(contours[hole])) continue;
    // The mean of both outlines' centres: the ring's width errs the same way on both.
    out.push_back({(centroid(contours[i]) + centroid(contours[hole])) * 0.5, area});
  }
  std::sort(out.begin(), out.end(), [](const Candidate& a, const Candidate& b) { return a.area > b.area; });
  return out;
}

}  // namespace

cv::Size photo_size(const std::string& b, const std::string& what) {
  cv::Size s;
  static const std::string kPng("\x89PNG\r\n\x1a\n", 8);
  if (b.size() >= 24 && b.compare(0, 8, kPng) == 0 && b.compare(12, 4, "IHDR") == 0) {
    s = {static_cast<int>(std::min(be32(b, 16), 1ul << 30)), static_cast<int>(std::min(be32(b, 20), 1ul << 30))};
  } else if (b.size() >= 4 && static_cast<unsigned char>(b[0]) == 0xFF && static_cast<unsigned char>(b[1]) == 0xD8) {
    s = jpeg_size(b);
  } else {
    throw InputError(what + ": not a PNG or JPEG photo");
  }
  if (s.width <= 0 || s.height <= 0) throw InputError(what + ": unreadable image header");
  const long long pixels = static_cast<long long>(s.width) * s.height;
  if (pixels > kMaxPhotoPixels) {
    throw InputError(what + ": " + std::to_string(s.width) + "x" + std::to_string(s.height) +
                     " pixels, more than the limit of " + std::to_string(kMaxPhotoPixels / 1'000'000) +
                     " megapixels; scale the photo down");
  }
  if (s.width < 64 || s.height < 64) throw InputError(what + ": smaller than 64x64 pixels");
  return s;
}

cv::Mat load_photo(const std::string& path) {
  const std::string what = "measure.photo = " + path;
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(path, ec);
  if (ec) throw InputError(what + ": cannot read (" + ec.message() + ")");
  if (bytes > static_cast<std::uintmax_t>(kMaxPhotoBytes)) {
    throw InputError(what + ": larger than " + std::to_string(kMaxPhotoBytes / 1'000'000) + " MB");
  }
  const std::string data = slicer::read_file(path);
  const cv::Size expected = photo_size(data, what);
  // Decoded with stb_image (libstb, as slicer/image does), not OpenCV's imgcodecs: that one
  // loads GDAL and a hundred libraries into every strand run (0.3 s and 45 MB at start-up).
  int w = 0, h = 0, channels = 0;
  stbi_uc* rgb = stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(data.data()),
                                       static_cast<int>(data.size()), &w, &h, &channels, 3);
  if (!rgb || w != expected.width || h != expected.height) {
    if (rgb) stbi_image_free(rgb);
    throw InputError(what + ": the image data cannot be decoded");
  }
  cv::Mat img;
  cv::cvtColor(cv::Mat(h, w, CV_8UC3, rgb), img, cv::COLOR_RGB2BGR);
  stbi_image_free(rgb);
  return img;
}

std::string encode_png(const cv::Mat& bgr) {
  cv::Mat rgb;
  cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
  std::string out;
  const auto append = [](void* context, void* bytes, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(bytes), static_cast<std::size_t>(size));
  };
  if (!stbi_write_png_to_func(append, &out, rgb.cols, rgb.rows, 3, rgb.data, static_cast<int>(rgb.step)))
    throw std::runtime_error("PNG encoding failed");
  return out;
}

FoundMarks find_marks(const cv::Mat& photo, const std::vector<Fiducial>& marks, const std::string& what) {
  cv::Mat gray;
  cv::cvtColor(photo, gray, cv::COLOR_BGR2GRAY);
  FoundMarks found;
  std::vector<Candidate> best;
  for (bool dark : {true, false}) {
    auto c = ring_candidates(gray, dark);
    if (c.size() >= marks.size()) {
      best = std::move(c);
      found.dark_ink = dark;
      break;
    }
    if (c.size() > best.size()) best = std::move(c);
  }
  if (best.size() < marks.size() || marks.size() < 4) {
    throw InputError(what + ": found " + std::to_string(best.size()) + " of the " + std::to_string(marks.size()) +
                     " fiducial marks (square rings at the corners); photograph the whole print, in focus");
  }
  best.resize(marks.size());
  // Pair by angle round the centre (photo y points down: flipped to the bed's sense).
  cv::Point2d pc(0, 0), bc(0, 0);
  for (const auto& c : best) pc += c.centre;
  for (const auto& m : marks) bc += cv::Point2d(m.x_mm, m.y_mm);
  pc *= 1.0 / best.size();
  bc *= 1.0 / marks.size();
  std::vector<std::pair<double, std::size_t>> pa, ba;
  for (std::size_t i = 0; i < best.size(); ++i) {
    pa.push_back({angle_about(cv::Point2d(best[i].centre.x, -best[i].centre.y), cv::Point2d(pc.x, -pc.y)), i});
    ba.push_back({angle_about(cv::Point2d(marks[i].x_mm, marks[i].y_mm), bc), i});
  }
  std::sort(pa.begin(), pa.end());
  std::sort(ba.begin(), ba.end());
  const std::size_t n = marks.size();
  std::size_t shift = 0;
  double least = 1e300;
  for (std::size_t s = 0; s < n; ++s) {
    double sum = 0;
    for (std::size_t k = 0; k < n; ++k) sum += std::abs(wrapped(pa[(k + s) % n].first - ba[k].first));
    if (sum < least) { least = sum; shift = s; }
  }
  found.centres_px.resize(n);
  for (std::size_t k = 0; k < n; ++k) found.centres_px[ba[k].second] = best[pa[(k + shift) % n].second].centre;
  return found;
}

Rectified rectify(const cv::Mat& photo, const std::vector<Fiducial>& marks, const FoundMarks& found,
                  double px_per_mm, double margin_mm) {
  Rectified r;
  r.dark_ink = found.dark_ink;
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (const auto& m : marks) {
    x0 = std::min(x0, m.x_mm - m.size_mm / 2);
    x1 = std::max(x1, m.x_mm + m.size_mm / 2);
    y0 = std::min(y0, m.y_mm - m.size_mm / 2);
    y1 = std::max(y1, m.y_mm + m.size_mm / 2);
  }
  r.x_min_mm = x0 - margin_mm;
  r.y_max_mm = y1 + margin_mm;
  const double w_mm = x1 - x0 + 2 * margin_mm, h_mm = y1 - y0 + 2 * margin_mm;
  // At most 40 megapixels of view: coarser when the print is large.
  r.px_per_mm = std::min(px_per_mm, std::sqrt(40e6 / (w_mm * h_mm)));
  std::vector<cv::Point2f> src, dst;
  for (std::size_t i = 0; i < 4; ++i) {
    src.emplace_back(found.centres_px[i]);
    dst.emplace_back(r.to_px(marks[i].x_mm, marks[i].y_mm));
  }
  const cv::Mat h = cv::getPerspectiveTransform(src, dst);
  const cv::Size size(static_cast<int>(std::ceil(w_mm * r.px_per_mm)), static_cast<int>(std::ceil(h_mm * r.px_per_mm)));
  cv::warpPerspective(photo, r.color, h, size, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  cv::Mat g;
  cv::cvtColor(r.color, g, cv::COLOR_BGR2GRAY);
  g.convertTo(r.gray, CV_32F);
  return r;
}

float sample(const cv::Mat& gray, double x, double y) {
  const int ix = static_cast<int>(std::floor(x)), iy = static_cast<int>(std::floor(y));
  if (ix < 0 || iy < 0 || ix + 1 >= gray.cols || iy + 1 >= gray.rows) return 0.0f;
  const float fx = static_cast<float>(x - ix), fy = static_cast<float>(y - iy);
  const float* r0 = gray.ptr<float>(iy);
  const float* r1 = gray.ptr<float>(iy + 1);
  return (r0[ix] * (1 - fx) + r0[ix + 1] * fx) * (1 - fy) + (r1[ix] * (1 - fx) + r1[ix + 1] * fx) * fy;
}

}  // namespace strand::post::measure
