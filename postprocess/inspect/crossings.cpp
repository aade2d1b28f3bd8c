// Per-layer contact search: CGAL's box_self_intersection_d on the touch-inflated bounding
// boxes of the segments reports the k pairs whose boxes overlap in O(n log^2 n + k),
// whatever the segment lengths (a uniform grid goes quadratic on a serpentine of long
// rows); each candidate pair is then classified exactly.
#include "postprocess/inspect/crossings.h"

#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "postprocess/plan/arc_segmentation.h"

namespace strand::post {

using slicer::Vec2;

namespace {

using Seg = ContactStream::Seg;

bool adjacent(const Seg& s, const Seg& t) {
  return s.strand == t.strand && std::abs(s.index - t.index) == 1;
}

struct Found {
  std::uint32_t i, j;
  slicer::Contact kind;
  bool operator<(const Found& o) const { return std::tie(i, j) < std::tie(o.i, o.j); }
  bool operator==(const Found& o) const { return i == o.i && j == o.j; }
};

// Classifies one candidate pair.
void test_pair(const std::vector<Seg>& segs, std::uint32_t i, std::uint32_t j, double touch,
               std::vector<Found>& found) {
  const Seg& s = segs[i];
  const Seg& t = segs[j];
  if (adjacent(s, t)) return;
  // Cheap reject: boxes apart by more than `touch` (most pairs sharing a cell).
  if (std::max(s.a.x(), s.b.x()) + touch < std::min(t.a.x(), t.b.x()) ||
      std::max(t.a.x(), t.b.x()) + touch < std::min(s.a.x(), s.b.x()) ||
      std::max(s.a.y(), s.b.y()) + touch < std::min(t.a.y(), t.b.y()) ||
      std::max(t.a.y(), t.b.y()) + touch < std::min(s.a.y(), s.b.y())) {
    return;
  }
  const auto c = slicer::segment_contact(s.a, s.b, t.a, t.b, touch);
  // A joint between consecutive moves split into chords is not a touch.
  if (c == slicer::Contact::None || (c == slicer::Contact::Touch && s.move == t.move)) return;
  found.push_back({std::min(i, j), std::max(i, j), c});
}

Vec2 touch_point(const Seg& s, const Seg& t, double touch) {
  if (slicer::point_segment_distance(t.a, s.a, s.b) <= touch) return t.a;
  if (slicer::point_segment_distance(t.b, s.a, s.b) <= touch) return t.b;
  return slicer::point_segment_distance(s.a, t.a, t.b) <= touch ? s.a : s.b;
}

// A segment's bounding box grown by `pad` on every side; its handle is the segment itself.
using SegBox = CGAL::Box_intersection_d::Box_with_handle_d<double, 2, const Seg*>;

SegBox box_of(const Seg& s, double pad) {
  double lo[2] = {std::min(s.a.x(), s.b.x()) - pad, std::min(s.a.y(), s.b.y()) - pad};
  double hi[2] = {std::max(s.a.x(), s.b.x()) + pad, std::max(s.a.y(), s.b.y()) + pad};
  return SegBox(lo, hi, &s);
}

void check_layer(int layer, const std::vector<Seg>& segs, double touch, ContactReport& out) {
  if (segs.size() < 2) return;
  // Boxes grown by the whole touch distance: a superset of the pairs test_pair accepts.
  std::vector<SegBox> boxes;
  boxes.reserve(segs.size());
  for (const Seg& s : segs) boxes.push_back(box_of(s, touch));
  std::vector<Found> found;
  const Seg* const base = segs.data();
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const SegBox& p, const SegBox& q) {
    test_pair(segs, static_cast<std::uint32_t>(p.handle() - base),
              static_cast<std::uint32_t>(q.handle() - base), touch, found);
  });
  std::sort(found.begin(), found.end());
  found.erase(std::unique(found.begin(), found.end()), found.end());
  for (const Found& f : found) {
    const Seg& s = segs[f.i];
    const Seg& t = segs[f.j];
    const bool walls = s.wall && t.wall;
    if (f.kind == slicer::Contact::Crossing) {
      out.crossings.push_back({layer, slicer::crossing_point(s.a, s.b, t.a, t.b), s.move, t.move,
                               s.line, t.line, walls, s.tool, t.tool});
    } else {
      out.touches.push_back(
          {layer, touch_point(s, t, touch), s.move, t.move, s.line, t.line, walls, s.tool, t.tool});
    }
  }
}

bool by_move(const Contact& a, const Contact& b) {
  return std::tie(a.layer, a.move_a, a.move_b, a.at_mm.x(), a.at_mm.y()) <
         std::tie(b.layer, b.move_a, b.move_b, b.at_mm.x(), b.at_mm.y());
}

}  // namespace

ContactStream::ContactStream(double tol, double touch, const slicer::Vec3& start_mm)
    : tol_(tol), touch_(touch), at_(start_mm) {}

// Flattens deposits into the layer's segments with strand ids; a new layer first searches
// the one before.
void ContactStream::add(const slicer::Move& mv, std::size_t move, int line, ContactReport& out) {
  if (mv.kind == slicer::MoveKind::Raw || mv.kind == slicer::MoveKind::Dwell) return;
  if (mv.layer != layer_) {
    search_layer(out);
    layer_ = mv.layer;
    depositing_ = false;
  }
  if (mv.kind != slicer::MoveKind::Deposit) {
    if ((mv.end_mm - at_).norm() > 0) depositing_ = false;
    at_ = mv.end_mm;
    return;
  }
  if (!depositing_) ++strand_, index_ = 0;
  depositing_ = true;
  const bool wall = mv.feature == slicer::Feature::Wall;
  Vec2 from = at_.head<2>();
  if (mv.is_arc) {
    for (const Vec2& q : segment_arc(from, mv.center_mm, mv.end_mm.head<2>(), mv.ccw, tol_)) {
      segs_.push_back({from, q, move, strand_, index_++, line, wall, mv.tool});
      from = q;
    }
  } else if ((mv.end_mm.head<2>() - from).norm() > 0) {
    segs_.push_back({from, mv.end_mm.head<2>(), move, strand_, index_++, line, wall, mv.tool});
  }
  at_ = mv.end_mm;
}

void ContactStream::search_layer(ContactReport& out) {
  const std::size_t crossings = out.crossings.size(), touches = out.touches.size();
  check_layer(layer_, segs_, touch_, out);
  std::stable_sort(out.crossings.begin() + static_cast<std::ptrdiff_t>(crossings),
                   out.crossings.end(), by_move);
  std::stable_sort(out.touches.begin() + static_cast<std::ptrdiff_t>(touches), out.touches.end(),
                   by_move);
  segs_.clear();
}

void ContactStream::finish(ContactReport& out) { search_layer(out); }

ContactReport find_contacts(const slicer::MotionProgram& p, double tol, double touch) {
  ContactReport out;
  ContactStream stream(tol, touch, p.start_mm);
  for (std::size_t i = 0; i < p.moves.size(); ++i) stream.add(p.moves[i], i, 0, out);
  stream.finish(out);
  // Layers in program order are sorted already; a program that returns to a layer is not.
  std::stable_sort(out.crossings.begin(), out.crossings.end(), by_move);
  std::stable_sort(out.touches.begin(), out.touches.end(), by_move);
  return out;
}

}  // namespace strand::post
