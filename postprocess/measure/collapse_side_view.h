// A side photo of a printed collapse test (patterns/collapse_test.h) rectified onto the
// upright plane of its filament. The bed's marks cannot be seen from the side, so the pillars
// are the marks (collapse_pillars.h): their corners are mapped to their known faces and
// heights.
#pragma once

#include <opencv2/core.hpp>
#include <string>

#include "postprocess/measure/collapse_pillars.h"

namespace strand::post::measure {

// The photo seen square-on from the front: pixel (c, r) is plane point
// (x_min_mm + c / px_per_mm, z_max_mm - r / px_per_mm).
struct SideView {
  cv::Mat color;  // BGR 8 bit
  cv::Mat ink;    // CV_32F share of the pillars' ink: 0 on the backdrop and the bed, 1 on ink
  double px_per_mm = 10.0;
  double x_min_mm = 0.0;
  double z_max_mm = 0.0;
  bool dark_ink = true;
  bool mirrored = false;    // taken from the back: x runs right to left in the photo
  double contrast = 0.0;    // the pillars' ink against the backdrop (share of the backdrop)
  double edge_mm = 0.0;     // 20-80 % width of the pillars' side faces: the photo's blur
  double fit_rms_mm = 0.0;  // the pillars' corners off the fitted mapping (rms)
  cv::Point2d to_px(double x_mm, double z_mm) const {
    return {(x_mm - x_min_mm) * px_per_mm, (z_max_mm - z_mm) * px_per_mm};
  }
  double x_of(double col) const { return x_min_mm + col / px_per_mm; }
  double z_of(double row) const { return z_max_mm - row / px_per_mm; }
};

// Finds the row's pillars in the photo (ink darker or lighter than the backdrop, uneven light
// flattened) and maps the photo onto the plane through a homography fitted to their corners;
// the view spans the row plus `margin_mm` at `px_per_mm` (less if the view would pass 20
// megapixels). InputError "WHAT: ..." for a photo from above (the bed's marks seen), what
// find_pillars refuses, corners that do not fit one plane, a photo upside down, or blur wider
// than the filament can stand.
SideView rectified_side_view(const cv::Mat& photo, const PillarRow& row, double px_per_mm, double margin_mm,
                             const std::string& what);

}  // namespace strand::post::measure
