// Room postprocess/measure (library strand_measure; links slicer and OpenCV): a photo of a
// printed ink test, read safely, its fiducial marks found and the bed plane rectified, so
// widths can be measured in millimetres whatever the camera's tilt and distance.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace strand::post::measure {

// Largest photo decoded: 60 megapixels (a 24 MP camera's frame fits with room to spare;
// 60 MP of 8-bit colour is 180 MB). Checked from the file header before decoding.
inline constexpr long long kMaxPhotoPixels = 60'000'000;
inline constexpr long long kMaxPhotoBytes = 200'000'000;

// A square mark of the test, in the part frame of its report (mm).
struct Fiducial {
  double x_mm = 0.0;
  double y_mm = 0.0;
  double size_mm = 0.0;
};

// Width and height read from a PNG or JPEG header; InputError for any other format, a
// truncated header or a frame above kMaxPhotoPixels.
cv::Size photo_size(const std::string& bytes, const std::string& what);
// Reads and decodes a PNG or JPEG (BGR, 8 bit) after the header check.
cv::Mat load_photo(const std::string& path);
// A BGR 8-bit image as PNG bytes (the overlay; the tests' synthetic photos).
std::string encode_png(const cv::Mat& bgr);

// Marks found in the photo, in the order of `marks` (pixel centres).
struct FoundMarks {
  std::vector<cv::Point2d> centres_px;
  bool dark_ink = true;  // ink darker than the bed
};
// Finds the closed square marks (a ring: an outline with a hole); InputError "found N of the
// M fiducial marks" when fewer than marks.size() are seen. The photo must be roughly upright
// (turned less than 45 deg) so that marks pair up by their angle round the centre.
FoundMarks find_marks(const cv::Mat& photo, const std::vector<Fiducial>& marks, const std::string& what);

// The photo seen from straight above: pixel (0, 0) is bed point (x_min_mm, y_max_mm), x to
// the right, y down (bed y up), px_per_mm pixels per millimetre.
struct Rectified {
  cv::Mat color;  // BGR 8 bit
  cv::Mat gray;   // CV_32F, 0-255
  double px_per_mm = 10.0;
  double x_min_mm = 0.0;
  double y_max_mm = 0.0;
  bool dark_ink = true;
  cv::Point2d to_px(double x_mm, double y_mm) const {
    return {(x_mm - x_min_mm) * px_per_mm, (y_max_mm - y_mm) * px_per_mm};
  }
};
// Maps the photo onto the bed plane through the homography that takes the found marks to
// their report positions; the view spans the marks plus `margin_mm`.
Rectified rectify(const cv::Mat& photo, const std::vector<Fiducial>& marks, const FoundMarks& found,
                  double px_per_mm, double margin_mm);

// Bilinear sample of a CV_32F image; 0 outside.
float sample(const cv::Mat& gray, double x_px, double y_px);

}  // namespace strand::post::measure
