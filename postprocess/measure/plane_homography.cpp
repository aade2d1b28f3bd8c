// The normalised direct linear transform: the homography as the null vector of the stacked
// point equations, through an SVD (OpenCV core; no calib3d).
#include "postprocess/measure/plane_homography.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace strand::post::measure {

namespace {

// Moves the points' centroid to the origin and scales their mean distance from it to sqrt 2.
cv::Matx33d normaliser(const std::vector<cv::Point2d>& p) {
  cv::Point2d c(0, 0);
  for (const auto& q : p) c += q;
  c *= 1.0 / static_cast<double>(p.size());
  double d = 0.0;
  for (const auto& q : p) d += std::hypot(q.x - c.x, q.y - c.y);
  d /= static_cast<double>(p.size());
  const double s = d > 0 ? std::sqrt(2.0) / d : 1.0;
  return {s, 0, -s * c.x, 0, s, -s * c.y, 0, 0, 1};
}

}  // namespace

cv::Point2d apply(const cv::Matx33d& h, const cv::Point2d& p) {
  const cv::Vec3d q = h * cv::Vec3d(p.x, p.y, 1.0);
  return {q[0] / q[2], q[1] / q[2]};
}

cv::Matx33d fit_homography(const std::vector<cv::Point2d>& from, const std::vector<cv::Point2d>& to) {
  assert(from.size() == to.size() && from.size() >= 4);
  const cv::Matx33d ta = normaliser(from), tb = normaliser(to);
  cv::Mat a(static_cast<int>(2 * from.size()), 9, CV_64F, cv::Scalar(0));
  for (std::size_t i = 0; i < from.size(); ++i) {
    const cv::Point2d p = apply(ta, from[i]), q = apply(tb, to[i]);
    double* r0 = a.ptr<double>(static_cast<int>(2 * i));
    double* r1 = a.ptr<double>(static_cast<int>(2 * i + 1));
    const double e0[9] = {-p.x, -p.y, -1, 0, 0, 0, q.x * p.x, q.x * p.y, q.x};
    const double e1[9] = {0, 0, 0, -p.x, -p.y, -1, q.y * p.x, q.y * p.y, q.y};
    std::copy(e0, e0 + 9, r0);
    std::copy(e1, e1 + 9, r1);
  }
  cv::Mat h;
  cv::SVD::solveZ(a, h);
  cv::Matx33d hn;
  for (int k = 0; k < 9; ++k) hn(k / 3, k % 3) = h.at<double>(k);
  cv::Matx33d out = tb.inv() * hn * ta;
  if (std::abs(out(2, 2)) > 1e-300) out *= 1.0 / out(2, 2);
  return out;
}

}  // namespace strand::post::measure
