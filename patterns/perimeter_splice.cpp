// Splicing: nearest loop point to a strand end, a crossing-free link, the loop rotated to
// start there.
#include "patterns/perimeter_splice.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <limits>
#include <optional>

#include "patterns/strand_chains.h"

namespace strand::patterns {

using slicer::Stroke;
using slicer::Vec2;

namespace {

// Link tolerance: loops lie one gap outside the fill boundary; allow rounding of offsets.
constexpr double kLinkSlack = 1.05;
// The longest stretch of a loop left out where it joins two strands (gaps).
constexpr double kMaxOpening = 2.0;

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

// Arc length from the first point to each point of a polyline.
std::vector<double> cumulative(const std::vector<Vec2>& p) {
  std::vector<double> cum{0.0};
  for (std::size_t i = 0; i + 1 < p.size(); ++i) cum.push_back(cum.back() + (p[i + 1] - p[i]).norm());
  return cum;
}

Vec2 end_of(const Stroke& s, bool at_start) { return at_start ? s.start_mm : s.end_mm(); }

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

// The closest pair of points of two closed loops (vertex of one to an edge of the other).
struct Neck {
  Nearest on_a, on_b;
  double distance = std::numeric_limits<double>::infinity();
};

Neck neck_between(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  Neck best;
  for (int side = 0; side < 2; ++side) {
    const auto& from = side == 0 ? a : b;
    const auto& to = side == 0 ? b : a;
    for (std::size_t i = 0; i + 1 < from.size(); ++i) {
      const Nearest n = nearest_on(to, from[i]);
      if (n.distance >= best.distance) continue;
      const Nearest here{i, from[i], n.distance};
      best.distance = n.distance;
      best.on_a = side == 0 ? here : n;
      best.on_b = side == 0 ? n : here;
    }
  }
  return best;
}

// Arc length along a closed loop's points (last repeats first) to a point on edge `e`.
double loop_position(const std::vector<Vec2>& loop, const std::vector<double>& cum,
                     const Nearest& n) {
  return cum[n.edge] + (n.at - loop[n.edge]).norm();
}

// The loop's vertices from n1 round the long way to n2 (neither point included): against the
// loop's order when n2 lies `d` > 0 ahead of n1 along it, with it otherwise.
std::vector<Vec2> long_way(const std::vector<Vec2>& loop, const Nearest& n1, const Nearest& n2, double d) {
  const std::size_t m = loop.size() - 1;
  std::vector<Vec2> round;
  if (d > 0) {
    for (std::size_t k = 0; k < m; ++k) {
      const std::size_t v = (n1.edge + m - k) % m;
      round.push_back(loop[v]);
      if (v == (n2.edge + 1) % m) break;
    }
  } else {
    for (std::size_t k = 1; k <= m; ++k) {
      const std::size_t v = (n1.edge + k) % m;
      round.push_back(loop[v]);
      if (v == n2.edge) break;
    }
  }
  return round;
}

// A loop no strand end took, spliced into the middle of a strand that runs beside it: the
// strand leaves at q1 for the loop's p1, runs round the loop the long way to p2 and comes back
// at q2, a gap further along; the strand between q1 and q2 and the loop between p1 and p2
// (each about a gap long) are left out, so the two links lie side by side, a gap apart, and
// close the loop's opening. Only straight stretches of the strand are used. The first place
// along the strand where both links are clear is taken (deterministic). `all` gains the links.
bool splice_into_middle(Stroke& s, const std::vector<Vec2>& loop, double gap_mm,
                        std::vector<const Stroke*>& all, std::deque<Stroke>& links) {
  const std::size_t m = loop.size() - 1;
  if (m < 3 || s.segments.empty()) return false;
  const std::vector<double> loop_cum = cumulative(loop);
  const double loop_length = loop_cum.back();
  // The strand's vertices and arc lengths (arcs count as their chords: never split).
  const std::vector<Vec2> ps = points_of(s);
  const std::vector<double> cum = cumulative(ps);
  const auto at = [&](double t, std::size_t& seg) {
    seg = static_cast<std::size_t>(std::upper_bound(cum.begin(), cum.end(), t) - cum.begin());
    seg = std::clamp<std::size_t>(seg, 1, ps.size() - 1) - 1;  // segment seg: ps[seg] -> ps[seg+1]
    const double len = cum[seg + 1] - cum[seg];
    const double f = len > 0.0 ? std::clamp((t - cum[seg]) / len, 0.0, 1.0) : 0.0;
    return Vec2(ps[seg] + f * (ps[seg + 1] - ps[seg]));
  };
  const double step = gap_mm / 4.0, reach = kLinkSlack * gap_mm;
  // Work bound: samples along the strand times the loop's edges.
  const double samples = cum.back() / step;
  if (samples * static_cast<double>(m) > 2e7) return false;
  for (double t = step; t + gap_mm < cum.back() - step; t += step) {
    std::size_t k1 = 0, k2 = 0;
    const Vec2 q1 = at(t, k1), q2 = at(t + gap_mm, k2);
    bool straight = true;
    for (std::size_t k = k1; k <= k2; ++k) straight = straight && s.segments[k].kind == slicer::SegmentKind::Line;
    if (!straight) continue;
    const Nearest n1 = nearest_on(loop, q1);
    if (n1.distance > reach || n1.distance < 0.5 * gap_mm) continue;
    const Nearest n2 = nearest_on(loop, q2);
    if (n2.distance > reach || n2.distance < 0.5 * gap_mm) continue;
    double d = loop_position(loop, loop_cum, n2) - loop_position(loop, loop_cum, n1);
    if (d > loop_length / 2) d -= loop_length;
    if (d < -loop_length / 2) d += loop_length;
    if (std::abs(d) < 0.5 * gap_mm || std::abs(d) > 2.0 * gap_mm) continue;
    if (slicer::segment_contact(q1, n1.at, q2, n2.at, 1e-9) != slicer::Contact::None) continue;
    if (!link_is_clear(q1, n1.at, all) || !link_is_clear(q2, n2.at, all)) continue;
    const std::vector<Vec2> round = long_way(loop, n1, n2, d);
    Stroke out = s;
    out.segments.assign(s.segments.begin(), s.segments.begin() + static_cast<std::ptrdiff_t>(k1));
    const auto add = [&](const Vec2& p, slicer::Feature f) {
      const Vec2 from = out.segments.empty() ? out.start_mm : out.segments.back().end_mm;
      if ((p - from).norm() > 1e-9) out.segments.push_back(slicer::line_to(p, f));
    };
    add(q1, s.segments[k1].feature);
    add(n1.at, slicer::Feature::Wall);
    for (const Vec2& p : round) add(p, slicer::Feature::Wall);
    add(n2.at, slicer::Feature::Wall);
    add(q2, slicer::Feature::Wall);
    add(s.segments[k2].end_mm, s.segments[k2].feature);
    out.segments.insert(out.segments.end(), s.segments.begin() + static_cast<std::ptrdiff_t>(k2) + 1,
                        s.segments.end());
    links.push_back({q1, {slicer::line_to(n1.at, slicer::Feature::Wall)}});
    all.push_back(&links.back());
    links.push_back({q2, {slicer::line_to(n2.at, slicer::Feature::Wall)}});
    all.push_back(&links.back());
    s = std::move(out);
    return true;
  }
  return false;
}

// Loops no strand took, joined in pairs where two lie within two bead widths of each other
// (a neck the pattern does not fill): round the first from the neck, across, round the
// second. A loop is entered and left at one point, so a pair is as far as a chain goes.
std::vector<Stroke> pair_loops(std::vector<Stroke> loops, double gap_mm,
                               std::vector<const Stroke*> all) {
  std::vector<Stroke> out;
  std::vector<bool> done(loops.size(), false);
  std::vector<Stroke> links;
  links.reserve(loops.size());
  for (std::size_t i = 0; i < loops.size(); ++i) {
    if (done[i]) continue;
    done[i] = true;
    const std::vector<Vec2> pi = points_of(loops[i]);
    std::size_t pick = loops.size();
    Neck best;
    for (std::size_t j = i + 1; j < loops.size(); ++j) {
      if (done[j]) continue;
      const Neck n = neck_between(pi, points_of(loops[j]));
      if (n.distance < best.distance) best = n, pick = j;
    }
    if (pick == loops.size() || best.distance > 2.0 * gap_mm ||
        !link_is_clear(best.on_a.at, best.on_b.at, all)) {
      out.push_back(loops[i]);
      continue;
    }
    done[pick] = true;
    links.push_back({best.on_a.at, {slicer::line_to(best.on_b.at, slicer::Feature::Wall)}});
    all.push_back(&links.back());
    Stroke joined = loops[i];
    const std::vector<Vec2> first = rotated(pi, best.on_a);
    const std::vector<Vec2> second = rotated(points_of(loops[pick]), best.on_b);
    joined.start_mm = first.front();
    joined.segments.clear();
    for (std::size_t k = 1; k < first.size(); ++k)
      joined.segments.push_back(slicer::line_to(first[k], slicer::Feature::Wall));
    for (const Vec2& q : second) joined.segments.push_back(slicer::line_to(q, slicer::Feature::Wall));
    out.push_back(std::move(joined));
  }
  return out;
}

// Strands joined in pairs through a loop beside an end of each: from the first's end across
// to the loop, round it the long way, across to the second's end. Per loop, of the strand ends
// beside it (within kLinkSlack gap, link clear) the two neighbours along it of different
// chains that lie closest, 0.5 to kMaxOpening gaps apart: that stretch of the loop, between
// the two links, is all it leaves out. A loop is entered and left once, so it joins one pair;
// chains never close on themselves. Returns the chains; `used` marks the loops taken, `all`
// and `links` gain the links.
std::vector<Stroke> join_through_loops(const std::vector<Stroke>& loops, const std::vector<Stroke>& strands,
                                       double gap_mm, std::vector<bool>& used, std::vector<const Stroke*>& all,
                                       std::deque<Stroke>& links) {
  struct End {
    std::size_t strand;
    bool at_start;
    Nearest n;
    double pos;
  };
  struct Join {
    End a, b;
    std::size_t loop;
    double d;  // b's position along the loop less a's, the short way
  };
  std::vector<std::size_t> root(strands.size());
  for (std::size_t i = 0; i < root.size(); ++i) root[i] = i;
  const auto find = [&](std::size_t i) {
    while (root[i] != i) i = root[i] = root[root[i]];
    return i;
  };
  EndJoins join_at(strands.size(), {-1, -1});  // per end: the join taken
  std::vector<Join> joins;
  const double reach = kLinkSlack * gap_mm;
  for (std::size_t l = 0; l < loops.size(); ++l) {
    if (used[l]) continue;
    const std::vector<Vec2> loop = points_of(loops[l]);
    if (loop.size() < 4) continue;
    const std::vector<double> cum = cumulative(loop);
    const double length = cum.back();
    std::vector<End> ends;
    for (std::size_t s = 0; s < strands.size(); ++s) {
      for (const bool at_start : {true, false}) {
        if (join_at[s][at_start ? 0 : 1] >= 0) continue;
        const Vec2 e = end_of(strands[s], at_start);
        const Nearest n = nearest_on(loop, e);
        if (n.distance > reach || !link_is_clear(e, n.at, all)) continue;
        ends.push_back({s, at_start, n, loop_position(loop, cum, n)});
      }
    }
    if (ends.size() < 2) continue;
    std::stable_sort(ends.begin(), ends.end(), [](const End& x, const End& y) { return x.pos < y.pos; });
    std::optional<Join> best;
    for (std::size_t i = 0; i < ends.size(); ++i) {
      const End& a = ends[i];
      const End& b = ends[(i + 1) % ends.size()];
      if (find(a.strand) == find(b.strand)) continue;
      double d = b.pos - a.pos;
      if (d < 0) d += length;
      if (d < 0.5 * gap_mm || d > kMaxOpening * gap_mm || d > length / 2) continue;
      if (slicer::segment_contact(end_of(strands[a.strand], a.at_start), a.n.at,
                                  end_of(strands[b.strand], b.at_start), b.n.at, 1e-9) != slicer::Contact::None) continue;
      if (!best || d < best->d) best = Join{a, b, l, d};
    }
    if (!best) continue;
    used[l] = true;
    root[find(best->a.strand)] = find(best->b.strand);
    join_at[best->a.strand][best->a.at_start ? 0 : 1] = static_cast<int>(joins.size());
    join_at[best->b.strand][best->b.at_start ? 0 : 1] = static_cast<int>(joins.size());
    for (const End* e : {&best->a, &best->b}) {
      links.push_back({end_of(strands[e->strand], e->at_start), {slicer::line_to(e->n.at, slicer::Feature::Wall)}});
      all.push_back(&links.back());
    }
    joins.push_back(*best);
  }
  if (joins.empty()) return strands;
  // Each chain from a strand with a free end: strand, link, round the loop, link, next strand.
  const auto bridge = [&](Stroke& chain, std::size_t j, std::size_t s, bool leaves_at_start) {
    const Join& jn = joins[j];
    const bool from_a = jn.a.strand == s && jn.a.at_start == leaves_at_start;
    const End& exit = from_a ? jn.a : jn.b;
    const End& entry = from_a ? jn.b : jn.a;
    const std::vector<Vec2> loop = points_of(loops[jn.loop]);
    chain.segments.push_back(slicer::line_to(exit.n.at, slicer::Feature::Wall));
    for (const Vec2& p : long_way(loop, exit.n, entry.n, from_a ? jn.d : -jn.d))
      chain.segments.push_back(slicer::line_to(p, slicer::Feature::Wall));
    chain.segments.push_back(slicer::line_to(entry.n.at, slicer::Feature::Wall));
    const Vec2 next = end_of(strands[entry.strand], entry.at_start);
    chain.segments.push_back(slicer::line_to(next, slicer::Feature::Wall));
    return std::pair<std::size_t, bool>{entry.strand, entry.at_start};
  };
  return chain_strands(strands, join_at, bridge);
}

}  // namespace

std::vector<Stroke> splice_loops(std::vector<Stroke> loops, std::vector<Stroke> strands,
                                 double gap_mm, const std::vector<Stroke>& others) {
  std::vector<bool> used(loops.size(), false);
  std::vector<const Stroke*> all;
  for (const Stroke& s : loops) all.push_back(&s);
  for (const Stroke& s : strands) all.push_back(&s);
  for (const Stroke& s : others) all.push_back(&s);
  std::deque<Stroke> links;  // links made so far, as strokes, so later links avoid them
  const std::vector<Stroke> chains = join_through_loops(loops, strands, gap_mm, used, all, links);
  std::vector<Stroke> out;
  for (const Stroke& s : chains) {
    Stroke joined = s;
    for (const bool at_start : {true, false}) {
      const Vec2 end = end_of(s, at_start);
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
  std::deque<Stroke> middle_links;  // stable addresses: `all` points at them
  std::vector<Stroke> left;
  for (std::size_t l = 0; l < loops.size(); ++l) {
    if (used[l]) continue;
    const std::vector<Vec2> ring = points_of(loops[l]);
    bool spliced = false;
    for (Stroke& s : out) {
      if (splice_into_middle(s, ring, gap_mm, all, middle_links)) {
        spliced = true;
        break;
      }
    }
    if (!spliced) left.push_back(loops[l]);
  }
  for (Stroke& s : pair_loops(std::move(left), gap_mm, all)) out.push_back(std::move(s));
  return out;
}

}  // namespace strand::patterns
