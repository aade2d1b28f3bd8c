// Chiral specimen border. Boundary nodes of odd degree are paired by frame edges that run
// along the border polygon (the boundary cycle offset beyond the attach circles), so every
// degree is even; the grip tabs are detours of a bottom and a top frame chord.
#include "patterns/chiral_border.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "slicer/units.h"

namespace strand::patterns {

using slicer::Feature;
using slicer::Vec2;

namespace {

// Grip detour replacing the frame chord p0 -> p1: a solid zig-zag of lines across the
// whole width (x_lo..x_hi along the chord), outside the chord by one pitch, entered and
// left through two neighbouring lines at the chord's middle; when a line falls outside
// the chord it is reached by a feeder half a pitch out. `mark` gets the start of the
// return line under the block, where the layer strand starts and ends.
void add_grip(EdgePath& path, const Vec2& p0, const Vec2& p1, double x_lo, double x_hi,
              double pitch_mm, double grip_mm, Vec2& mark) {
  const double len = (p1 - p0).norm();
  const Vec2 u = (p1 - p0) / len, n(u.y(), -u.x());  // n: outward for a ccw border
  auto at = [&](double x, double y) { return Vec2(p0 + x * u + y * n); };
  int lines = static_cast<int>(std::ceil((x_hi - x_lo) / pitch_mm - 1e-9)) + 1;
  lines += lines % 2;
  const double sp = (x_hi - x_lo) / (lines - 1);
  auto xl = [&](int i) { return x_lo + i * sp; };
  int i1 = 0;  // the last even line left of the middle enters, the next one leaves
  for (int i = 0; i + 1 < lines; i += 2) {
    if (xl(i) < len / 2) i1 = i;
  }
  const double eps = sp / 16, y_feed = pitch_mm / 2;
  const double xa = std::clamp(xl(i1), eps, len / 2 - eps);
  const double xb = std::clamp(xl(i1 + 1), len / 2 + eps, len - eps);
  const double y_top = pitch_mm, y_ret = pitch_mm + grip_mm, y_bot = y_ret - sp;
  path.add(at(xa, 0), Feature::Frame);
  if (xa != xl(i1))
    path.add(at(xa, y_feed), Feature::Grip), path.add(at(xl(i1), y_feed), Feature::Grip);
  double y = 0;
  for (int i = i1; i >= 0; --i) {
    if (i != i1) path.add(at(xl(i), y), Feature::Grip);
    y = (i1 - i) % 2 == 0 ? (i == 0 ? y_ret : y_bot) : y_top;
    path.add(at(xl(i), y), Feature::Grip);
  }
  mark = at(xl(0), y_ret);
  for (int i = lines - 1; i > i1; --i) {
    path.add(at(xl(i), y), Feature::Grip);
    y = (lines - 1 - i) % 2 == 0 ? (i == i1 + 1 ? (xb != xl(i) ? y_feed : 0.0) : y_top) : y_bot;
    path.add(at(xl(i), y), Feature::Grip);
  }
  if (xb != xl(i1 + 1)) path.add(at(xb, y_feed), Feature::Grip), path.add(at(xb, 0), Feature::Grip);
  path.add(p1, Feature::Frame);
}

// A frame edge pairs odd boundary nodes a and b (indices into odd_positions) along the
// border polygon of its level; level 1 runs one layer height outside level 0 and nests
// over a level-0 pair.
struct FramePair {
  int a = 0, b = 0, level = 0;
};

struct Border {
  std::vector<Vec2> poly[2];
  std::vector<int> odd_positions;  // boundary positions of odd-degree nodes
  std::vector<FramePair> pairs;
  int grip_chords[2] = {-1, -1};  // boundary positions k of chords k -> k + 1
  int grip_pair[2] = {-1, -1};    // the outermost pair covering each grip chord
};

// Position of chord k among the odd nodes: it lies between odd j and j + 1 (cyclic).
int odd_index_before(const Border& b, int k) {
  const int m = static_cast<int>(b.odd_positions.size());
  int count = 0;
  for (int pos : b.odd_positions) count += pos <= k ? 1 : 0;
  return (count - 1 + m) % m;
}

// The chord of [first, last) nearest the middle whose odd index has parity `parity`
// (any parity when parity < 0); -1 when there is none.
int pick_chord(const Border& b, int first, int last, int parity) {
  const int m = static_cast<int>(b.odd_positions.size());
  int pick = -1;
  for (int k = first; k < last; ++k) {
    if (parity >= 0 && (odd_index_before(b, k) - parity + m) % 2 != 0) continue;
    if (pick < 0 || std::abs(2 * k + 1 - first - last) < std::abs(2 * pick + 1 - first - last))
      pick = k;
  }
  return pick;
}

// Pairs odd nodes so that a frame edge covers one chord of the bottom and of the top row
// (the grips): consecutive pairs when one parity serves both, else the top chord's
// neighbours are re-paired as an inner pair plus an outer pair nested over it.
void choose_frame(Border& b, int bottom_first, int bottom_last, int top_first, int top_last,
                  int nb) {
  const int m = static_cast<int>(b.odd_positions.size());
  int offset = -1;
  for (int o = 0; o < 2 && offset < 0; ++o) {
    b.grip_chords[0] = pick_chord(b, bottom_first, bottom_last, o);
    b.grip_chords[1] = pick_chord(b, top_first, top_last, o);
    if (b.grip_chords[0] >= 0 && b.grip_chords[1] >= 0) offset = o;
  }
  int nest = -1;
  if (offset < 0) {
    if (m < 4) throw std::logic_error("chiral frame: too few odd nodes to reach both grips");
    b.grip_chords[0] = pick_chord(b, bottom_first, bottom_last, -1);
    b.grip_chords[1] = pick_chord(b, top_first, top_last, -1);
    offset = odd_index_before(b, b.grip_chords[0]) % 2;
    nest = odd_index_before(b, b.grip_chords[1]);  // pairs nest-1, nest and nest+1, nest+2 change
  }
  for (int t = offset; t < m + offset; t += 2) {
    if (nest >= 0 && (t % m == (nest - 1 + m) % m || t % m == (nest + 1) % m)) continue;
    b.pairs.push_back({t % m, (t + 1) % m, 0});
  }
  if (nest >= 0) {
    b.pairs.push_back({nest, (nest + 1) % m, 0});
    b.pairs.push_back({(nest - 1 + m) % m, (nest + 2) % m, 1});
  }
  for (int side = 0; side < 2; ++side) {
    for (int i = 0; i < static_cast<int>(b.pairs.size()); ++i) {
      const int ka =
          b.odd_positions[static_cast<std::size_t>(b.pairs[static_cast<std::size_t>(i)].a)];
      const int kb =
          b.odd_positions[static_cast<std::size_t>(b.pairs[static_cast<std::size_t>(i)].b)];
      const bool covers = (b.grip_chords[side] - ka + nb) % nb < (kb - ka + nb) % nb;
      const int best = b.grip_pair[side];
      if (covers && (best < 0 || b.pairs[static_cast<std::size_t>(i)].level >
                                     b.pairs[static_cast<std::size_t>(best)].level)) {
        b.grip_pair[side] = i;
      }
    }
  }
}

// Extent of `poly` along the chord p0 -> p1, measured from p0.
std::pair<double, double> extent_along(const std::vector<Vec2>& poly, const Vec2& p0,
                                       const Vec2& p1) {
  const Vec2 u = (p1 - p0).normalized();
  double lo = 1e300, hi = -1e300;
  for (const Vec2& p : poly) lo = std::min(lo, (p - p0).dot(u)), hi = std::max(hi, (p - p0).dot(u));
  return {lo, hi};
}

}  // namespace

FrameAttach frame_attach(const Vec2& c, const std::vector<double>& ligament_angles,
                         const NodeRings& rings, const Vec2& p) {
  const double theta = slicer::angle_of(c, p);
  double closest = slicer::kTwoPi, tau = theta;
  for (double a : ligament_angles) {
    const double cw = slicer::wrap_period(theta - a, slicer::kTwoPi);
    if (cw < closest) closest = cw, tau = a;
  }
  FrameAttach f;
  if (closest >= std::acos(rings.attach_mm / (p - c).norm())) {
    f.angle_rad = theta;
    f.pts = {c + rings.attach_mm * slicer::unit_vector(theta)};
    return f;
  }
  f.angle_rad = tau - std::acos(rings.attach_mm / rings.frame_mm) / 2;
  f.pts = {c + rings.attach_mm * slicer::unit_vector(f.angle_rad), c + rings.frame_mm * slicer::unit_vector(f.angle_rad)};
  return f;
}

namespace {

void add_frame(ChiralFrame& b, const ChiralLattice& l, const NodeRings& rings, const Border& border,
               const std::vector<std::vector<double>>& end_angles, double nozzle_mm,
               double grip_mm) {
  const int nb = static_cast<int>(l.boundary.size());
  for (int i = 0; i < static_cast<int>(border.pairs.size()); ++i) {
    const FramePair& fp = border.pairs[static_cast<std::size_t>(i)];
    const auto& poly = border.poly[fp.level];
    const int ka = border.odd_positions[static_cast<std::size_t>(fp.a)];
    const int kb = border.odd_positions[static_cast<std::size_t>(fp.b)];
    const int va = l.boundary[static_cast<std::size_t>(ka)],
              vb = l.boundary[static_cast<std::size_t>(kb)];
    const Vec2 ca = l.nodes[static_cast<std::size_t>(va)],
               cb = l.nodes[static_cast<std::size_t>(vb)];
    const FrameAttach fa = frame_attach(ca, end_angles[static_cast<std::size_t>(va)], rings,
                                        poly[static_cast<std::size_t>(ka)]);
    const FrameAttach fb = frame_attach(cb, end_angles[static_cast<std::size_t>(vb)], rings,
                                        poly[static_cast<std::size_t>(kb)]);
    EdgePath path;
    path.pts.push_back(fa.pts.front());
    if (fa.pts.size() > 1) path.add(fa.pts.back(), Feature::Frame);
    for (int k = ka;; k = (k + 1) % nb) {
      path.add(poly[static_cast<std::size_t>(k)], Feature::Frame);
      if (k == kb) break;
      for (int side = 0; side < 2; ++side) {
        if (k != border.grip_chords[side] || border.grip_pair[side] != i || grip_mm <= 0) continue;
        const Vec2 p0 = poly[static_cast<std::size_t>(k)],
                   p1 = poly[static_cast<std::size_t>((k + 1) % nb)];
        const auto [x_lo, x_hi] =
            extent_along(border.poly[0], p0, p1);  // grips as wide as the frame
        Vec2 mark;
        add_grip(path, p0, p1, x_lo, x_hi, nozzle_mm, grip_mm, mark);
        path.pts.pop_back(), path.feats.pop_back();  // the loop adds the chord's end
        if (side == 0) b.mark = mark, b.grip_edge = static_cast<int>(b.edges.size());
      }
    }
    for (auto it = fb.pts.rbegin(); it != fb.pts.rend(); ++it) path.add(*it, Feature::Frame);
    b.edges.push_back({va, vb, fa.angle_rad, fb.angle_rad, std::move(path)});
  }
}

}  // namespace

ChiralFrame chiral_frame(const ChiralLattice& l, const NodeRings& rings,
                         const std::vector<std::vector<double>>& end_angles, double nozzle_mm,
                         double grip_mm) {
  ChiralFrame b;
  Border border;
  border.poly[0] = border_polygon(l, rings.frame_mm);
  border.poly[1] = border_polygon(l, 2 * rings.frame_mm - rings.attach_mm);
  const int nb = static_cast<int>(l.boundary.size());
  auto node_at = [&](int k) { return l.boundary[static_cast<std::size_t>(k)]; };
  auto y_at = [&](int k) { return l.nodes[static_cast<std::size_t>(node_at(k))].y(); };
  for (int k = 0; k < nb; ++k) {
    if (end_angles[static_cast<std::size_t>(node_at(k))].size() % 2 != 0) {
      border.odd_positions.push_back(k);
    }
  }
  if (border.odd_positions.empty()) throw std::logic_error("chiral frame: no odd boundary node");
  // bottom row: boundary positions 0..bottom_last; top row: as many, from the first node at
  // the largest y (the boundary runs counter-clockwise from the bottom-left node)
  int bottom_last = 0, top_first = 0;
  while (bottom_last + 1 < nb && y_at(bottom_last + 1) == y_at(0)) ++bottom_last;
  while (y_at(top_first) != l.nodes.back().y()) ++top_first;
  choose_frame(border, 0, bottom_last, top_first, top_first + bottom_last, nb);
  add_frame(b, l, rings, border, end_angles, nozzle_mm, grip_mm);
  return b;
}

}  // namespace strand::patterns
