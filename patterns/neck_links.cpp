// Neck links: candidate pairs of strand ends by length, each checked against every segment.
#include "patterns/neck_links.h"

#include <algorithm>
#include <array>
#include <numeric>

#include "patterns/strand_chains.h"
#include "slicer/geometry.h"

namespace strand::patterns {

using slicer::Stroke;
using slicer::Vec2;

namespace {

struct Link {
  std::size_t a, b;       // strands
  bool a_start, b_start;  // which end of each
  double length;
};

Vec2 end_of(const Stroke& s, bool at_start) { return at_start ? s.start_mm : s.end_mm(); }

// Whether segments p1-p2 and q1-q2 come closer than `clear` (boxes first: most are far).
bool closer_than(const Vec2& p1, const Vec2& p2, const Vec2& q1, const Vec2& q2, double clear) {
  if (std::max(q1.x(), q2.x()) < std::min(p1.x(), p2.x()) - clear ||
      std::min(q1.x(), q2.x()) > std::max(p1.x(), p2.x()) + clear ||
      std::max(q1.y(), q2.y()) < std::min(p1.y(), p2.y()) - clear ||
      std::min(q1.y(), q2.y()) > std::max(p1.y(), p2.y()) + clear)
    return false;
  if (slicer::segment_contact(p1, p2, q1, q2, 1e-12) == slicer::Contact::Crossing) return true;
  return std::min({slicer::point_segment_distance(p1, q1, q2),
                   slicer::point_segment_distance(p2, q1, q2),
                   slicer::point_segment_distance(q1, p1, p2),
                   slicer::point_segment_distance(q2, p1, p2)}) < clear;
}

// Every segment of `s` at least `clear` from p-q. When the link leaves from one of s's ends
// (`own` 0: its start, 1: its end), the segments within `clear` of that end along s are not
// counted: they lead to the link.
bool stroke_clear(const Stroke& s, const Vec2& p, const Vec2& q, double clear, int own = -1) {
  const double total = own == 1 ? slicer::stroke_length(s) : 0.0;
  double along = 0.0;  // from the start to the segment's start
  Vec2 from = s.start_mm;
  for (const auto& seg : s.segments) {
    const double len = (seg.end_mm - from).norm();
    const bool lead = (own == 0 && along < clear) || (own == 1 && total - along - len < clear);
    if (!lead && closer_than(p, q, from, seg.end_mm, clear)) return false;
    along += len;
    from = seg.end_mm;
  }
  return true;
}

bool inside(const slicer::Region& region, const std::vector<slicer::Ring>& rings, const Vec2& p,
            const Vec2& q, double clear) {
  if (!slicer::contains(region, (p + q) / 2.0)) return false;
  for (const auto& ring : rings) {
    for (std::size_t i = 0; i < ring.size(); ++i) {
      if (closer_than(p, q, ring[i], ring[(i + 1) % ring.size()], clear)) return false;
    }
  }
  return true;
}

}  // namespace

std::vector<Stroke> link_across_necks(std::vector<Stroke> strands,
                                      const std::vector<Stroke>& others,
                                      const slicer::Region& region, const NeckLinkOptions& o) {
  std::vector<Link> links;
  for (std::size_t a = 0; a < strands.size(); ++a) {
    for (std::size_t b = std::max(a + 1, o.from); b < strands.size(); ++b) {
      for (const bool as : {true, false}) {
        for (const bool bs : {true, false}) {
          const double len = (end_of(strands[a], as) - end_of(strands[b], bs)).norm();
          if (len <= o.reach_mm) links.push_back({a, b, as, bs, len});
        }
      }
    }
  }
  if (links.empty()) return strands;
  const std::vector<slicer::Ring> rings = slicer::rings_of(region);
  std::stable_sort(links.begin(), links.end(),
                   [](const Link& x, const Link& y) { return x.length < y.length; });
  std::vector<std::size_t> root(strands.size());
  std::iota(root.begin(), root.end(), std::size_t{0});
  const auto find = [&](std::size_t i) {
    while (root[i] != i) i = root[i] = root[root[i]];
    return i;
  };
  EndJoins link_at(strands.size(), {-1, -1});  // per end: the link taken
  std::vector<Link> taken;
  std::vector<Stroke> drawn;  // the links taken, as strokes, so later links keep clear of them
  drawn.reserve(links.size());
  for (const Link& l : links) {
    if (find(l.a) == find(l.b) || link_at[l.a][l.a_start ? 0 : 1] >= 0 ||
        link_at[l.b][l.b_start ? 0 : 1] >= 0)
      continue;
    const Vec2 p = end_of(strands[l.a], l.a_start), q = end_of(strands[l.b], l.b_start);
    bool clear = inside(region, rings, p, q, o.edge_mm);
    for (std::size_t s = 0; clear && s < strands.size(); ++s) {
      const int own = s == l.a ? (l.a_start ? 0 : 1) : s == l.b ? (l.b_start ? 0 : 1) : -1;
      clear = stroke_clear(strands[s], p, q, o.clearance_mm, own);
    }
    for (std::size_t s = 0; clear && s < others.size(); ++s)
      clear = stroke_clear(others[s], p, q, o.clearance_mm);
    for (std::size_t s = 0; clear && s < drawn.size(); ++s)
      clear = stroke_clear(drawn[s], p, q, o.clearance_mm);
    if (!clear) continue;
    root[find(l.a)] = find(l.b);
    link_at[l.a][l.a_start ? 0 : 1] = link_at[l.b][l.b_start ? 0 : 1] =
        static_cast<int>(taken.size());
    taken.push_back(l);
    drawn.push_back({p, {slicer::line_to(q, slicer::Feature::Wall)}});
  }
  if (taken.empty()) return strands;
  return chain_strands(
      strands, link_at, [&](Stroke& chain, std::size_t j, std::size_t s, bool leaves_at_start) {
        const Link& l = taken[j];
        const bool from_a = l.a == s && l.a_start == leaves_at_start;
        const std::size_t next = from_a ? l.b : l.a;
        const bool at_start = from_a ? l.b_start : l.a_start;
        const slicer::Feature f =
            chain.segments.empty() ? slicer::Feature::Infill : chain.segments.back().feature;
        chain.segments.push_back(slicer::line_to(end_of(strands[next], at_start), f));
        return std::pair<std::size_t, bool>{next, at_start};
      });
}

}  // namespace strand::patterns
