// Splicing: nearest loop point to a strand end, a crossing-free link, the loop rotated to
// start there.
#include "patterns/perimeter_splice.h"

#include <algorithm>
#include <limits>

namespace strand::patterns {

using slicer::Stroke;
using slicer::Vec2;

namespace {

// Link tolerance: loops lie one gap outside the fill boundary; allow rounding of offsets.
constexpr double kLinkSlack = 1.05;

struct Nearest {
  std::size_t edge = 0;  // from vertex edge to edge + 1 of the loop's points
  Vec2 at = Vec2::Zero();
  double distance = std::numeric_limits<double>::infinity();
};

std::vector<Vec2> points_of(const Stroke& s) {
  std::vector<Vec2> p{s.start_mm};
  for (const auto& seg : s.segments) p.push_back(seg.end_mm);
  return p;
}

Nearest nearest_on(const std::vector<Vec2>& loop, const Vec2& q) {
  Nearest best;
  for (std::size_t i = 0; i + 1 < loop.size(); ++i) {
    const Vec2 a = loop[i], ab = loop[i + 1] - a;
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0 ? std::clamp((q - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    const Vec2 p = a + t * ab;
    if ((p - q).norm() < best.distance) best = {i, p, (p - q).norm()};
  }
  return best;
}

// True when segment a-b meets no stroke segment except at a or b themselves.
bool link_is_clear(const Vec2& a, const Vec2& b, const std::vector<const Stroke*>& strokes) {
  constexpr double kEps = 1e-9;
  for (const Stroke* s : strokes) {
    const std::vector<Vec2> p = points_of(*s);
    for (std::size_t i = 0; i + 1 < p.size(); ++i) {
      const auto c = slicer::segment_contact(a, b, p[i], p[i + 1], kEps);
      if (c == slicer::Contact::None) continue;
      const bool at_end = slicer::point_segment_distance(a, p[i], p[i + 1]) < kEps ||
                          slicer::point_segment_distance(b, p[i], p[i + 1]) < kEps;
      if (c == slicer::Contact::Crossing || !at_end) return false;
    }
  }
  return true;
}

// The loop as points from `n.at` round to `n.at` again.
std::vector<Vec2> rotated(const std::vector<Vec2>& loop, const Nearest& n) {
  std::vector<Vec2> out{n.at};
  const std::size_t m = loop.size() - 1;  // closed: last point repeats the first
  for (std::size_t k = 1; k <= m; ++k) out.push_back(loop[(n.edge + k) % m]);
  out.push_back(n.at);
  return out;
}

}  // namespace

std::vector<Stroke> splice_loops(std::vector<Stroke> loops, std::vector<Stroke> strands,
                                 double gap_mm, const std::vector<Stroke>& others) {
  std::vector<bool> used(loops.size(), false);
  std::vector<const Stroke*> all;
  for (const Stroke& s : loops) all.push_back(&s);
  for (const Stroke& s : strands) all.push_back(&s);
  for (const Stroke& s : others) all.push_back(&s);
  std::vector<Stroke> links;  // links made so far, as strokes, so later links avoid them
  links.reserve(2 * strands.size());
  std::vector<Stroke> out;
  for (Stroke& s : strands) {
    Stroke joined = s;
    for (const bool at_start : {true, false}) {
      const Vec2 end = at_start ? s.start_mm : s.end_mm();
      std::size_t pick = loops.size();
      Nearest best;
      for (std::size_t l = 0; l < loops.size(); ++l) {
        if (used[l]) continue;
        const Nearest n = nearest_on(points_of(loops[l]), end);
        if (n.distance < best.distance) best = n, pick = l;
      }
      if (pick == loops.size() || best.distance > kLinkSlack * gap_mm ||
          !link_is_clear(end, best.at, all))
        continue;
      used[pick] = true;
      links.push_back({end, {slicer::line_to(best.at, slicer::Feature::Wall)}});
      all.push_back(&links.back());
      std::vector<Vec2> ring = rotated(points_of(loops[pick]), best);
      Stroke next = joined;
      if (at_start) {
        next.start_mm = ring.front();
        next.segments.clear();
        for (std::size_t i = 1; i < ring.size(); ++i)
          next.segments.push_back(slicer::line_to(ring[i], slicer::Feature::Wall));
        next.segments.push_back(slicer::line_to(end, slicer::Feature::Wall));
        next.segments.insert(next.segments.end(), joined.segments.begin(), joined.segments.end());
      } else {
        next.segments.push_back(slicer::line_to(ring.front(), slicer::Feature::Wall));
        for (std::size_t i = 1; i < ring.size(); ++i)
          next.segments.push_back(slicer::line_to(ring[i], slicer::Feature::Wall));
      }
      joined = std::move(next);
    }
    out.push_back(std::move(joined));
  }
  for (std::size_t l = 0; l < loops.size(); ++l) {
    if (!used[l]) out.push_back(loops[l]);
  }
  return out;
}

}  // namespace strand::patterns
