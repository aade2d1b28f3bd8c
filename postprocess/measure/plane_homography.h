// A homography fitted to many point pairs (the normalised direct linear transform), for
// mapping a photo onto a plane from more marks than four, and its use on a point.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

namespace strand::post::measure {

// The least-squares homography taking each `from` point to its `to` point (at least 4 pairs,
// not all on one line); Hartley's normalisation of both sets keeps the system conditioned.
cv::Matx33d fit_homography(const std::vector<cv::Point2d>& from, const std::vector<cv::Point2d>& to);

// The homography applied to a point.
cv::Point2d apply(const cv::Matx33d& h, const cv::Point2d& p);

}  // namespace strand::post::measure
