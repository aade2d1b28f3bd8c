// Straight beads and square fiducial marks of the printed ink tests.
#include "patterns/ink_test_marks.h"

#include "slicer/params.h"

namespace strand::patterns {

using slicer::Vec2;

slicer::Stroke straight_bead(const Vec2& a, const Vec2& b, double width_mm, double height_mm,
                             slicer::Feature feature) {
  slicer::Stroke s;
  s.start_mm = a;
  s.segments.push_back(slicer::line_to(b, feature));
  s.width_mm = width_mm;
  s.height_mm = height_mm;
  return s;
}

slicer::Stroke square_mark(const Vec2& c, double side_mm, double width_mm, double height_mm) {
  const double h = side_mm / 2;
  slicer::Stroke s;
  s.start_mm = c + Vec2(-h, -h);
  for (const Vec2& corner : {Vec2(h, -h), Vec2(h, h), Vec2(-h, h), Vec2(-h, -h)}) {
    s.segments.push_back(slicer::line_to(c + corner, slicer::Feature::Frame));
  }
  s.width_mm = width_mm;
  s.height_mm = height_mm;
  return s;
}

nlohmann::json add_corner_marks(slicer::Layer& layer, double mx, double my, double size_mm, double nozzle_mm,
                                double height_mm) {
  nlohmann::json fiducials = nlohmann::json::array();
  for (const Vec2& c : {Vec2(mx, my), Vec2(-mx, my), Vec2(-mx, -my), Vec2(mx, -my)}) {
    layer.strokes.push_back(square_mark(c, size_mm, nozzle_mm, height_mm));
    fiducials.push_back({{"x_mm", c.x()}, {"y_mm", c.y()}, {"size_mm", size_mm}, {"shape", "square"}});
  }
  return fiducials;
}

void check_layer_and_marks(const std::string& test, double d, double layer_height_mm, double fiducial_mm,
                           std::vector<std::string>& problems) {
  if (layer_height_mm < 0.5 * d - 1e-12 || layer_height_mm > d + 1e-12) {
    problems.push_back(slicer::problem(test, "layer-height", layer_height_mm,
                                       "must be in [0.5, 1] x nozzle = [" + slicer::short_number(0.5 * d) + ", " +
                                           slicer::short_number(d) + "]",
                                       "mm"));
  }
  if (fiducial_mm < 4 * d - 1e-9) {
    problems.push_back(slicer::problem(test, "fiducial-size", fiducial_mm,
                                       "must be >= 4 x nozzle = " + slicer::short_number(4 * d), "mm"));
  }
}

}  // namespace strand::patterns
