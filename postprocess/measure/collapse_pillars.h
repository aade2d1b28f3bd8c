// The pillars of a collapse test (patterns/collapse_test.h) found in a side photo: the ink
// told from the backdrop and the bed under uneven light, the thin filament opened away, the
// blocks left ordered along the row and matched to the report's spacing either way round (a
// photo taken from the back shows the row mirrored), and each block's corners.
#pragma once

#include <array>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "postprocess/measure/photo.h"

namespace strand::post::measure {

// Least ink contrast against the backdrop, as a share of the backdrop's brightness.
inline constexpr double kLeastInkContrast = 0.12;

// The pillars as the report places them, in the upright plane (x along the row, z up).
struct PillarRow {
  std::vector<double> left_mm;  // each pillar's left face, x ascending
  double side_mm = 0.0;         // a pillar's width along x
  double top_mm = 0.0;          // top of a pillar's silhouette: the filament's top over it
  double nozzle_mm = 0.0;
  std::vector<Fiducial> marks;  // on the bed: seen in a photo from above, not from the side
};

// One pillar's block in the photo searched.
struct PillarBlock {
  cv::RotatedRect rect;
  std::vector<cv::Point> outline;  // its contour, corners rounded by the opening
};

struct FoundPillars {
  bool dark_ink = true;
  double contrast = 0.0;             // the ink's strength against the backdrop
  cv::Mat background;                // CV_32F: the backdrop's brightness, ink taken out
  std::vector<PillarBlock> blocks;   // in the photo's order along the row
  cv::Point2d along{1, 0};           // the row's direction in the photo, pointing right
  bool mirrored = false;             // the photo's left block is the report's last pillar
  double rounding_px = 0.0;          // radius of the opening that rounded the blocks' corners
};

// How far the photo departs from the backdrop towards the ink, as a share of the backdrop
// (0 to 2): 1 - gray / background for dark ink, gray / background - 1 for light.
cv::Mat ink_strength(const cv::Mat& gray, const cv::Mat& background, bool dark_ink);

// Finds the row's pillars in a grey photo (CV_32F, 0-255), dark ink first, then light.
// InputError "WHAT: ..." for too little contrast, a count of blocks other than the report's
// pillars, a row more than 45 deg off level or spaced otherwise than the report's.
FoundPillars find_pillars(const cv::Mat& gray, const PillarRow& row, const std::string& what);

// A block's corners, bottom-left, bottom-right, top-left, top-right as the photo shows them:
// the crossings of lines fitted to the straight middles of its four sides, each moved out half
// a pixel (the outline runs through the edge pixels' centres).
std::array<cv::Point2d, 4> pillar_corners(const PillarBlock& block, const cv::Point2d& along, double rounding_px);

}  // namespace strand::post::measure
