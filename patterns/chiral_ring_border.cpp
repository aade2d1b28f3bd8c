// Border of a ring lattice (a chiral lattice wrapped round a cylinder): nothing along the
// seam, frame edges pairing the odd nodes of each end row, and a grip band all round each
// end, entered and left from one frame edge (or a loop at one node) by two neighbouring
// lines of its serpentine.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "patterns/chiral_border.h"
#include "slicer/units.h"

namespace strand::patterns {

using slicer::Feature;
using slicer::Vec2;

namespace {

// Adds p unless the path already ends there (a loop's legs meet the band's first and last line).
void add_new(EdgePath& path, const Vec2& p, Feature f) {
  if ((path.pts.back() - p).norm() > 1e-9) path.add(p, f);
}

// One end of the lattice: its row of nodes in order of x, the frame line's y and which way
// is outward (-1 below the bottom row, +1 above the top row).
struct EndRow {
  std::vector<int> nodes;
  double frame_y = 0.0;
  double outward = 0.0;
};

EndRow end_row(const ChiralLattice& l, const NodeRings& rings, bool top) {
  EndRow e;
  auto y_of = [&](int n) { return l.nodes[static_cast<std::size_t>(n)].y(); };
  double y = y_of(0);
  for (int n = 0; n < static_cast<int>(l.nodes.size()); ++n)
    y = top ? std::max(y, y_of(n)) : std::min(y, y_of(n));
  for (int n = 0; n < static_cast<int>(l.nodes.size()); ++n) {
    if (y_of(n) == y) e.nodes.push_back(n);
  }
  std::sort(e.nodes.begin(), e.nodes.end(), [&](int a, int b) {
    return l.nodes[static_cast<std::size_t>(a)].x() < l.nodes[static_cast<std::size_t>(b)].x();
  });
  e.outward = top ? 1.0 : -1.0;
  e.frame_y = y + e.outward * rings.frame_mm;
  return e;
}

// The grip band, a detour of the frame chord at (x_in, y): out to the far edge, then a
// serpentine of lines across the band `sp` apart (about a nozzle, an even number of them)
// running once round in direction `dir` (against the chord's), back to the chord at
// x_in - dir * sp one period on. `mark` gets the far end of the first line.
void add_ring_grip(EdgePath& path, double x_in, double y, double outward, double dir,
                   double period_mm, double pitch_mm, double grip_mm, Vec2& mark) {
  int lines = static_cast<int>(std::ceil(period_mm / pitch_mm - 1e-9));
  lines += lines % 2;
  const double sp = period_mm / lines;
  const double y_near = y + outward * pitch_mm, y_far = y_near + outward * grip_mm;
  add_new(path, Vec2(x_in, y), Feature::Frame);
  path.add(Vec2(x_in, y_far), Feature::Grip);
  mark = Vec2(x_in, y_far);
  double at_y = y_far;
  for (int k = 1; k < lines; ++k) {
    const double x = x_in + dir * k * sp;
    path.add(Vec2(x, at_y), Feature::Grip);
    at_y = k + 1 == lines ? y : (k % 2 == 1 ? y_near : y_far);
    path.add(Vec2(x, at_y), Feature::Grip);
  }
  path.wrap += static_cast<int>(dir);
}

double grip_spacing(double period_mm, double pitch_mm) {
  int lines = static_cast<int>(std::ceil(period_mm / pitch_mm - 1e-9));
  return period_mm / (lines + lines % 2);
}

struct Leg {
  double angle_rad = 0.0;
  std::vector<Vec2> pts;  // from the attach circle out to (not including) the frame point
  Vec2 frame_pt = Vec2::Zero();
};

// The frame edge from leg `a` of node va to leg `b` of node vb along the frame line, with
// the grip band in the middle of its chord when `grip`.
FrameEdge ring_edge(const ChiralLattice& l, int va, int vb, const Leg& a, const Leg& b,
                    const EndRow& row, bool grip, double pitch_mm, double grip_mm, Vec2& mark) {
  EdgePath path;
  path.pts.push_back(a.pts.front());
  for (std::size_t k = 1; k < a.pts.size(); ++k) path.add(a.pts[k], Feature::Frame);
  path.add(a.frame_pt, Feature::Frame);
  if (grip) {
    const double dir = b.frame_pt.x() > a.frame_pt.x() ? -1.0 : 1.0;
    const double sp = grip_spacing(l.period_mm, pitch_mm);
    const double x_in = (a.frame_pt.x() + b.frame_pt.x()) / 2 + dir * sp / 2;
    add_ring_grip(path, x_in, row.frame_y, row.outward, dir, l.period_mm, pitch_mm, grip_mm, mark);
  }
  const Vec2 shift(path.wrap * l.period_mm, 0.0);
  add_new(path, b.frame_pt + shift, Feature::Frame);
  for (auto it = b.pts.rbegin(); it != b.pts.rend(); ++it) path.add(*it + shift, Feature::Frame);
  return {va, vb, a.angle_rad, b.angle_rad, std::move(path)};
}

Leg frame_leg(const ChiralLattice& l, const NodeRings& rings,
              const std::vector<std::vector<double>>& end_angles, int v, const EndRow& row) {
  const Vec2 c = l.nodes[static_cast<std::size_t>(v)];
  const Vec2 p(c.x(), row.frame_y);
  FrameAttach f = frame_attach(c, end_angles[static_cast<std::size_t>(v)], rings, p);
  return {f.angle_rad, std::move(f.pts), p};
}

// A loop at a node whose end row has no odd node: two radial legs, one straight out and one
// a grip line-spacing beside it, both in the gap the chirality leaves there (ligaments
// leave their tangent points counter-clockwise, so the gap lies clockwise of straight out).
std::pair<Leg, Leg> loop_legs(const ChiralLattice& l, const NodeRings& rings, int v,
                              const EndRow& row, double pitch_mm) {
  const Vec2 c = l.nodes[static_cast<std::size_t>(v)];
  const double out = row.outward > 0 ? slicer::kPi / 2 : -slicer::kPi / 2;
  const double sp = grip_spacing(l.period_mm, pitch_mm);
  const double side = std::atan(sp / rings.frame_mm);
  auto leg = [&](double angle) {
    const Vec2 at = c + rings.attach_mm * slicer::unit_vector(angle);
    const Vec2 p = c + rings.frame_mm / std::cos(out - angle) * slicer::unit_vector(angle);
    return Leg{angle, {at}, p};
  };
  return {leg(out - side), leg(out)};
}

void add_end(ChiralFrame& f, const ChiralLattice& l, const NodeRings& rings,
             const std::vector<std::vector<double>>& end_angles, const EndRow& row, double pitch_mm,
             double grip_mm, bool bottom) {
  std::vector<int> odd;
  for (int v : row.nodes) {
    if (end_angles[static_cast<std::size_t>(v)].size() % 2 != 0) odd.push_back(v);
  }
  if (odd.size() % 2 != 0) throw std::logic_error("chiral ring frame: odd count of odd end nodes");
  auto x_of = [&](int v) { return l.nodes[static_cast<std::size_t>(v)].x(); };
  int grip_pair = -1;  // the pair whose chord middle is nearest x = 0
  for (std::size_t k = 0; k + 1 < odd.size(); k += 2) {
    const double mid = std::abs(x_of(odd[k]) + x_of(odd[k + 1]));
    if (grip_pair < 0 || mid < std::abs(x_of(odd[static_cast<std::size_t>(grip_pair)]) +
                                        x_of(odd[static_cast<std::size_t>(grip_pair) + 1]))) {
      grip_pair = static_cast<int>(k);
    }
  }
  Vec2 mark = Vec2::Zero();
  for (std::size_t k = 0; k + 1 < odd.size(); k += 2) {
    const bool grip = grip_mm > 0 && static_cast<int>(k) == grip_pair;
    if (grip && bottom) f.grip_edge = static_cast<int>(f.edges.size());
    f.edges.push_back(ring_edge(l, odd[k], odd[k + 1], frame_leg(l, rings, end_angles, odd[k], row),
                                frame_leg(l, rings, end_angles, odd[k + 1], row), row, grip,
                                pitch_mm, grip_mm, mark));
    if (grip && bottom) f.mark = mark;
  }
  if (grip_mm > 0 && odd.empty()) {
    const int v = *std::min_element(row.nodes.begin(), row.nodes.end(), [&](int a, int b) {
      return std::abs(x_of(a)) < std::abs(x_of(b));
    });
    const auto [a, b] = loop_legs(l, rings, v, row, pitch_mm);
    if (bottom) f.grip_edge = static_cast<int>(f.edges.size());
    f.edges.push_back(ring_edge(l, v, v, a, b, row, true, pitch_mm, grip_mm, mark));
    if (bottom) f.mark = mark;
  }
}

}  // namespace

ChiralFrame chiral_ring_frame(const ChiralLattice& l, const NodeRings& rings,
                              const std::vector<std::vector<double>>& end_angles, double nozzle_mm,
                              double grip_mm) {
  ChiralFrame f;
  add_end(f, l, rings, end_angles, end_row(l, rings, false), nozzle_mm, grip_mm, true);
  add_end(f, l, rings, end_angles, end_row(l, rings, true), nozzle_mm, grip_mm, false);
  return f;
}

}  // namespace strand::patterns
