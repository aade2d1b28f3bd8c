// A binned screen-space depth test over projected triangles.
#include "postprocess/preview/preview_depth.h"

#include <algorithm>
#include <cmath>

namespace strand::post {

using slicer::Vec2;

DepthMap depth_map(std::vector<std::array<Vec2, 3>> screen,
                   std::vector<std::array<double, 3>> nearness, int width_px, int height_px) {
  DepthMap m;
  m.cols = std::max(1, static_cast<int>(std::ceil(width_px / m.cell_px)));
  m.rows = std::max(1, static_cast<int>(std::ceil(height_px / m.cell_px)));
  m.cells.resize(static_cast<std::size_t>(m.cols) * static_cast<std::size_t>(m.rows));
  for (std::size_t t = 0; t < screen.size(); ++t) {
    Vec2 lo = screen[t][0], hi = screen[t][0];
    for (const Vec2& p : screen[t]) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    const int c0 = std::max(0, static_cast<int>(std::floor(lo.x() / m.cell_px)));
    const int c1 = std::min(m.cols - 1, static_cast<int>(std::floor(hi.x() / m.cell_px)));
    const int r0 = std::max(0, static_cast<int>(std::floor(lo.y() / m.cell_px)));
    const int r1 = std::min(m.rows - 1, static_cast<int>(std::floor(hi.y() / m.cell_px)));
    for (int r = r0; r <= r1; ++r) {
      for (int c = c0; c <= c1; ++c) {
        m.cells[static_cast<std::size_t>(r * m.cols + c)].push_back(static_cast<int>(t));
      }
    }
  }
  m.screen = std::move(screen);
  m.nearness = std::move(nearness);
  return m;
}

bool behind(const DepthMap& m, const Vec2& at, double nearness_mm) {
  const int c = static_cast<int>(std::floor(at.x() / m.cell_px));
  const int r = static_cast<int>(std::floor(at.y() / m.cell_px));
  if (c < 0 || r < 0 || c >= m.cols || r >= m.rows) return false;
  for (int t : m.cells[static_cast<std::size_t>(r * m.cols + c)]) {
    const auto& [a, b, q] = m.screen[static_cast<std::size_t>(t)];
    const double area = (b - a).x() * (q - a).y() - (b - a).y() * (q - a).x();
    if (std::abs(area) < 1e-12) continue;
    const double wb = ((at - a).x() * (q - a).y() - (at - a).y() * (q - a).x()) / area;
    const double wc = ((b - a).x() * (at - a).y() - (b - a).y() * (at - a).x()) / area;
    if (wb < 0 || wc < 0 || wb + wc > 1) continue;
    const auto& n = m.nearness[static_cast<std::size_t>(t)];
    if ((1 - wb - wc) * n[0] + wb * n[1] + wc * n[2] > nearness_mm) return true;
  }
  return false;
}

}  // namespace strand::post
