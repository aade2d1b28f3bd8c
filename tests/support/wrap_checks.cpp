// Cylinder-topology checks for wrapped toolpaths (tests only).
#include "tests/support/wrap_checks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "postprocess/plan/arc_segmentation.h"

namespace strand::testing {

using slicer::Vec2;

namespace {

double wrapped_x(double x, double period) { return x - period * std::floor(x / period + 0.5); }

struct Box {
  Vec2 lo, hi;
};

Box box_of(const Vec2& a, const Vec2& b) { return {a.cwiseMin(b), a.cwiseMax(b)}; }

bool overlap(const Box& p, const Box& q, double dx) {
  return p.lo.x() <= q.hi.x() + dx && q.lo.x() + dx <= p.hi.x() && p.lo.y() <= q.hi.y() &&
         q.lo.y() <= p.hi.y();
}

}  // namespace

std::vector<std::pair<Vec2, Vec2>> flat_segments(const slicer::Stroke& s, double tol_mm) {
  std::vector<std::pair<Vec2, Vec2>> out;
  Vec2 at = s.start_mm;
  for (const auto& seg : s.segments) {
    if (seg.kind == slicer::SegmentKind::Line) {
      out.emplace_back(at, seg.end_mm);
    } else {
      for (const Vec2& q : post::segment_arc(at, seg.center_mm, seg.end_mm, seg.ccw, tol_mm)) {
        out.emplace_back(at, q);
        at = q;
      }
    }
    at = seg.end_mm;
  }
  return out;
}

std::vector<Vec2> wrapped_crossings(const slicer::Layer& layer, double period_mm) {
  std::vector<std::pair<Vec2, Vec2>> segs;
  for (const auto& s : layer.strokes) {
    for (auto [a, b] : flat_segments(s, 0.005)) {
      const double shift = wrapped_x(a.x(), period_mm) - a.x();  // start inside one period
      segs.emplace_back(a + Vec2(shift, 0), b + Vec2(shift, 0));
    }
  }
  std::vector<Box> boxes;
  for (const auto& [a, b] : segs) boxes.push_back(box_of(a, b));
  std::vector<Vec2> out;
  for (std::size_t i = 0; i < segs.size(); ++i) {
    for (std::size_t j = i + 1; j < segs.size(); ++j) {
      for (int k = -2; k <= 2; ++k) {
        const double dx = k * period_mm;
        if (!overlap(boxes[i], boxes[j], dx)) continue;
        const Vec2 c = segs[j].first + Vec2(dx, 0), d = segs[j].second + Vec2(dx, 0);
        if (slicer::segment_contact(segs[i].first, segs[i].second, c, d, 1e-9) ==
            slicer::Contact::Crossing) {
          const Vec2 p = slicer::crossing_point(segs[i].first, segs[i].second, c, d);
          out.emplace_back(wrapped_x(p.x(), period_mm), p.y());
        }
      }
    }
  }
  return out;
}

double wrapped_min_gap(const slicer::Layer& layer, double period_mm) {
  std::vector<std::pair<Vec2, Vec2>> segs;
  for (const auto& s : layer.strokes) {
    for (auto [a, b] : flat_segments(s, 0.005)) {
      const double shift = wrapped_x(a.x(), period_mm) - a.x();
      segs.emplace_back(a + Vec2(shift, 0), b + Vec2(shift, 0));
    }
  }
  double gap = 1e300;
  for (std::size_t i = 0; i < segs.size(); ++i) {
    const auto [a, b] = segs[i];
    for (std::size_t j = i + 1; j < segs.size(); ++j) {
      for (int k = -2; k <= 2; ++k) {
        const Vec2 c = segs[j].first + Vec2(k * period_mm, 0);
        const Vec2 d = segs[j].second + Vec2(k * period_mm, 0);
        const double joined = std::min({(a - c).norm(), (a - d).norm(), (b - c).norm(), (b - d).norm()});
        if (joined < 2e-3) continue;
        gap = std::min({gap, slicer::point_segment_distance(a, c, d),
                        slicer::point_segment_distance(b, c, d),
                        slicer::point_segment_distance(c, a, b),
                        slicer::point_segment_distance(d, a, b)});
      }
    }
  }
  return gap;
}

std::vector<std::vector<Vec2>> seam_pieces(const slicer::Stroke& s, double period_mm) {
  const double half = period_mm / 2;
  double shift = wrapped_x(s.start_mm.x(), period_mm) - s.start_mm.x();  // drawn = x + shift
  std::vector<std::vector<Vec2>> pieces = {{s.start_mm + Vec2(shift, 0)}};
  for (const auto& [a, b] : flat_segments(s, 0.005)) {
    Vec2 pa = a + Vec2(shift, 0);
    while (true) {  // cut a-b wherever it leaves [-half, half]
      const Vec2 pb = b + Vec2(shift, 0);
      if (std::abs(pb.x()) <= half) {
        pieces.back().push_back(pb);
        break;
      }
      const double edge = pb.x() > half ? half : -half;
      const Vec2 cut = pa + (edge - pa.x()) / (pb.x() - pa.x()) * (pb - pa);
      pieces.back().push_back(cut);
      shift -= 2 * edge;
      pa = cut - Vec2(2 * edge, 0);
      pieces.push_back({pa});
    }
  }
  return pieces;
}

double largest_seam_gap(const std::vector<std::vector<Vec2>>& pieces, double period_mm) {
  double gap = 0;
  for (std::size_t i = 0; i + 1 < pieces.size(); ++i) {
    const Vec2 d = pieces[i + 1].front() - pieces[i].back();
    gap = std::max(gap, std::hypot(wrapped_x(d.x(), period_mm), d.y()));
  }
  return gap;
}

void expect_sound_wrap(const slicer::Toolpath& t, double period_mm) {
  const auto& d = t.derived;
  ASSERT_TRUE(d.contains("cells_around") && d.contains("cell_around_mm")) << d.dump();
  EXPECT_NEAR(d.at("cells_around").get<int>() * d.at("cell_around_mm").get<double>(), period_mm,
              1e-9);
  EXPECT_NEAR(d.at("wrap_period_mm").get<double>(), period_mm, 1e-12);
  for (std::size_t k = 0; k < t.layers.size(); ++k) {
    SCOPED_TRACE("layer " + std::to_string(k));
    const auto& layer = t.layers[k];
    ASSERT_EQ(layer.strokes.size(), 1u) << "one strand per layer";
    if (k > 0 && layer.strokes == t.layers[k - 1].strokes) continue;  // identical layers
    const auto crossings = wrapped_crossings(layer, period_mm);
    EXPECT_TRUE(crossings.empty())
        << crossings.size() << " crossings, first at " << crossings.front().transpose();
    for (const auto& [a, b] : flat_segments(layer.strokes[0], 0.005)) {
      ASSERT_LT(std::abs(b.x() - a.x()), period_mm / 2)
          << "a segment spans half the period: " << a.transpose() << " -> " << b.transpose();
    }
    const auto pieces = seam_pieces(layer.strokes[0], period_mm);
    EXPECT_LT(largest_seam_gap(pieces, period_mm), 1e-6);
    for (const auto& piece : pieces) {
      for (const Vec2& p : piece) {
        ASSERT_LE(std::abs(p.x()), period_mm / 2 + 1e-9) << "piece outside one period";
      }
    }
  }
}

}  // namespace strand::testing
