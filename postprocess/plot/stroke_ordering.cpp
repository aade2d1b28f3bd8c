// Stroke merging, and per pen the start tour improved by 2-opt / Or-opt moves.
#include "postprocess/plot/stroke_ordering.h"

#include <algorithm>
#include <map>

#include "postprocess/plot/cyclic_tour.h"
#include "postprocess/plot/near_lists.h"
#include "postprocess/plot/point_grid.h"
#include "postprocess/plot/start_tour.h"

namespace strand::post {

namespace {

using slicer::Stroke;
using slicer::Vec2;

// a then b; a gap (at most the join distance) is bridged by a line so no geometry moves.
Stroke joined(Stroke a, const Stroke& b) {
  if ((b.start_mm - a.end_mm()).norm() > 0.0) {
    a.segments.push_back(slicer::line_to(b.start_mm, slicer::Feature::Pen));
  }
  for (const auto& s : b.segments) a.segments.push_back(s);
  return a;
}

// slicer::reversed without a copy: the same stroke drawn from its end (each segment ends at
// its old start and turns the other way).
void turn_round(Stroke& s) {
  auto& g = s.segments;
  if (g.empty()) return;
  const Vec2 end = g.back().end_mm;
  std::reverse(g.begin(), g.end());
  for (std::size_t k = 0; k + 1 < g.size(); ++k) g[k].end_mm = g[k + 1].end_mm;
  g.back().end_mm = s.start_mm;
  for (auto& seg : g) seg.ccw = !seg.ccw;
  s.start_mm = end;
}

double dist(const Vec2& a, const Vec2& b) { return (a - b).norm(); }

// Pens with at most this many strokes are ordered from both start tours (greedy and nearest
// neighbour) and keep the shorter: a few milliseconds, and the better start differs by drawing.
constexpr int kBothStartsMax = 5000;

// The k endpoints nearest `at`, nearest first (ties by id): one linear pass.
std::vector<int> nearest_to(const std::vector<Vec2>& ends, const Vec2& at, int k) {
  std::vector<std::pair<double, int>> by_distance(ends.size());
  for (std::size_t e = 0; e < ends.size(); ++e) {
    by_distance[e] = {(ends[e] - at).squaredNorm(), static_cast<int>(e)};
  }
  const std::size_t take = std::min(ends.size(), static_cast<std::size_t>(std::max(k, 0)));
  std::partial_sort(by_distance.begin(), by_distance.begin() + take, by_distance.end());
  std::vector<int> out(take);
  for (std::size_t i = 0; i < take; ++i) out[i] = by_distance[i].second;
  return out;
}

// 2-opt and Or-opt driven by candidate lists: for the edge a -> b leaving position p, try
// joining a to one of its near endpoints instead, or b to one of its own; move single
// strokes (either way round) next to a near endpoint.
class Improver {
 public:
  // near_start: endpoints nearest the start point, nearest first.
  Improver(CyclicTour& t, const NearLists& near, std::vector<int> near_start)
      : t_(t), near_(near), near_start_(std::move(near_start)) {}

  // Improves until no move within `span` positions helps or the budget is spent.
  void run(long& budget, int span) {
    span_ = span;
    std::vector<int> queue(t_.size());
    for (int p = 0; p < t_.size(); ++p) queue[t_.size() - 1 - p] = t_.stroke_at(p);
    std::vector<char> queued(t_.size(), 1);
    while (!queue.empty() && budget > 0) {
      const int s = queue.back();
      queue.pop_back();
      queued[s] = 0;
      const int p = t_.pos_of(s);
      bool improved = false;
      for (int edge_at : {p - 1, p}) {
        if (edge_at < -1 || edge_at + 1 >= t_.size()) continue;
        if (try_two_opt(edge_at, budget) || try_two_opt_from_b(edge_at, budget) ||
            try_or_opt(edge_at, budget) || try_from_start(edge_at, budget)) {
          improved = true;
          break;
        }
      }
      if (improved) {
        for (int q = std::max(0, p - 2); q < std::min(t_.size(), p + 3); ++q) {
          push(t_.stroke_at(q), queue, queued);
        }
        for (int s2 : touched_) push(s2, queue, queued);
      }
    }
  }

 private:
  static void push(int s, std::vector<int>& queue, std::vector<char>& queued) {
    if (!queued[s]) {
      queued[s] = 1;
      queue.push_back(s);
    }
  }

  // The first leg: reverse positions 0..q so the pen starts at a nearer endpoint, out(q)
  // (the start point has no candidate list of its own, so 2-opt never sees this edge).
  bool try_from_start(int p, long& budget) {
    if (p != -1) return false;
    const Vec2 start = t_.out_point(-1), b = t_.in_point(0);
    const double sb = dist(start, b);
    for (int c : near_start_) {
      --budget;
      const Vec2 cp = t_.ends_point(c);
      const double sc = dist(start, cp);
      if (sc >= sb) break;
      const int q = t_.pos_of(c / 2);
      if (c != t_.out(q) || q > span_) continue;
      // start -> out(q) ... in(0) -> in(q + 1)
      const double next =
          q + 1 < t_.size() ? dist(b, t_.in_point(q + 1)) - t_.edge(q) : -t_.edge(q);
      if (sc + next - sb < -1e-9) {
        apply_reverse(0, q);
        return true;
      }
    }
    return false;
  }

  bool try_two_opt(int p, long& budget) {
    if (p < 0) return false;
    const Vec2 a = t_.out_point(p), b = t_.in_point(p + 1);
    const double ab = dist(a, b);
    for (int c : near_[t_.out(p)]) {
      --budget;
      const Vec2 cp = t_.ends_point(c);
      const double ac = dist(a, cp);
      if (ac >= ab) break;
      const int q = t_.pos_of(c / 2);
      if (q > p && c == t_.out(q) && q - p <= span_) {
        // reverse [p+1 .. q]: a -> out(q), in(p+1) -> in(q+1)
        const double next =
            q + 1 < t_.size() ? dist(b, t_.in_point(q + 1)) - t_.edge(q) : -t_.edge(q);
        if (ac + next - ab < -1e-9) {
          apply_reverse(p + 1, q);
          return true;
        }
      } else if (q <= p && c == t_.in(q) && p - q <= span_) {
        // reverse [q .. p]: out(q-1) -> out(p) = a, in(q) = c -> b
        const Vec2 prev = t_.out_point(q - 1);
        const double delta = dist(prev, a) + dist(cp, b) - dist(prev, cp) - ab;
        if (delta < -1e-9) {
          apply_reverse(q, p);
          return true;
        }
      }
    }
    return false;
  }

  // The same moves found from b's candidates: a new edge c -> b.
  bool try_two_opt_from_b(int p, long& budget) {
    if (p < 0) return false;
    const Vec2 a = t_.out_point(p), b = t_.in_point(p + 1);
    const double ab = dist(a, b);
    for (int c : near_[t_.in(p + 1)]) {
      --budget;
      const Vec2 cp = t_.ends_point(c);
      const double bc = dist(b, cp);
      if (bc >= ab) break;
      const int q = t_.pos_of(c / 2);
      if (q > p + 1 && c == t_.in(q) && q - 1 - p <= span_) {
        // reverse [p+1 .. q-1]: a -> out(q-1), in(p+1) = b -> c = in(q)
        const Vec2 d = t_.out_point(q - 1);
        const double delta = dist(a, d) + bc - ab - dist(d, cp);
        if (delta < -1e-9) {
          apply_reverse(p + 1, q - 1);
          return true;
        }
      } else if (q <= p && c == t_.in(q) && p - q <= span_) {
        // reverse [q .. p]: out(q-1) -> out(p) = a, c = in(q) -> b
        const Vec2 prev = t_.out_point(q - 1);
        const double delta = dist(prev, a) + bc - dist(prev, cp) - ab;
        if (delta < -1e-9) {
          apply_reverse(q, p);
          return true;
        }
      }
    }
    return false;
  }

  // Moves the single stroke at p + 1 (either way round) next to a near endpoint of a.
  bool try_or_opt(int p, long& budget) {
    if (p + 1 >= t_.size()) return false;
    const int m = p + 1;
    const Vec2 prev = t_.out_point(m - 1), in_m = t_.in_point(m), out_m = t_.out_point(m);
    const bool last = m + 1 >= t_.size();
    const double removed = dist(prev, in_m) + (last ? 0.0 : dist(out_m, t_.in_point(m + 1)) -
                                                          dist(prev, t_.in_point(m + 1)));
    for (int c : near_[t_.in(m)]) {
      --budget;
      const int q = t_.pos_of(c / 2);
      if (q == m || c != t_.out(q) || std::abs(q - m) > span_) continue;
      const Vec2 cp = t_.ends_point(c);
      const bool q_last = q + 1 >= t_.size();
      const Vec2 nxt = q_last ? Vec2::Zero() : t_.in_point(q + 1);
      if (q + 1 == m) continue;
      const double added = dist(cp, in_m) + (q_last ? 0.0 : dist(out_m, nxt) - dist(cp, nxt));
      if (added - removed < -1e-9) {
        move_after(m, q);
        return true;
      }
    }
    // The stroke turned round: out(q) -> out(m) ... in(m) -> in(q + 1).
    for (int c : near_[t_.out(m)]) {
      --budget;
      const int q = t_.pos_of(c / 2);
      if (q == m || q + 1 == m || c != t_.out(q) || std::abs(q - m) > span_) continue;
      const Vec2 cp = t_.ends_point(c);
      const bool q_last = q + 1 >= t_.size();
      const Vec2 nxt = q_last ? Vec2::Zero() : t_.in_point(q + 1);
      const double added = dist(cp, out_m) + (q_last ? 0.0 : dist(in_m, nxt) - dist(cp, nxt));
      if (added - removed < -1e-9) {
        const int stroke = t_.stroke_at(m);
        move_after(m, q);
        const int at = t_.pos_of(stroke);
        t_.reverse_block(at, at);
        return true;
      }
    }
    return false;
  }

  void apply_reverse(int i, int j) {
    touched_ = {t_.stroke_at(i), t_.stroke_at(j)};
    t_.reverse_block(i, j);
  }

  // Moves the stroke at m to just after position q, keeping its direction.
  void move_after(int m, int q) {
    touched_ = {t_.stroke_at(m), t_.stroke_at(q)};
    t_.shift(m, q > m ? q : q + 1);
  }

  CyclicTour& t_;
  const NearLists& near_;
  std::vector<int> near_start_;
  std::vector<int> touched_;
  int span_ = 0;
};

// One pen's strokes (indices into `all`) in drawing order, each with whether to turn it
// round; the strokes themselves are copied once, by order_strokes.
// The pen's strokes (indices into `all`) grid cell by grid cell of their start points, so
// that strokes near each other on paper sit near each other in memory, and their endpoints in
// the metric space: ends[2s] the start of stroke s, ends[2s + 1] its end.
std::vector<int> members_by_cell(const std::vector<Stroke>& all, const std::vector<int>& members,
                                 const OrderOptions& o, std::vector<Vec2>& ends) {
  const std::size_t n = members.size();
  std::vector<Vec2> starts(n);
  for (std::size_t s = 0; s < n; ++s) {
    const Vec2& p = all[static_cast<std::size_t>(members[s])].start_mm;
    starts[s] = o.metric ? o.metric(p) : p;
  }
  std::vector<int> by_cell = PointGrid(starts).ids_by_cell();
  ends.resize(2 * n);
  for (std::size_t k = 0; k < n; ++k) {
    const Stroke& s = all[static_cast<std::size_t>(members[by_cell[k]])];
    ends[2 * k] = starts[by_cell[k]];
    ends[2 * k + 1] = o.metric ? o.metric(s.end_mm()) : s.end_mm();
    by_cell[k] = members[by_cell[k]];
  }
  return by_cell;
}

// A start tour improved: (stroke, entered by its end) in drawing order, and the pen-up length.
struct Improved {
  std::vector<std::pair<int, bool>> order;
  double length = 0.0;
};

Improved improve(const std::vector<Vec2>& ends, const std::vector<int>& order,
                 const std::vector<char>& reversed, const NearLists& near_by_stroke,
                 const OrderOptions& o, const Vec2& start_metric) {
  const int n = static_cast<int>(order.size());
  // Strokes relabelled in tour order: label k is stroke order[k].
  std::vector<Vec2> tour_ends(ends.size());
  std::vector<char> tour_reversed(n, 0);
  std::vector<int> label(n);
  for (int k = 0; k < n; ++k) {
    tour_ends[2 * k] = ends[2 * order[k]];
    tour_ends[2 * k + 1] = ends[2 * order[k] + 1];
    tour_reversed[k] = reversed[order[k]];
    label[order[k]] = k;
  }
  CyclicTour tour(std::move(tour_ends), start_metric, tour_reversed);
  const NearLists near = near_by_stroke.relabelled(label);
  long budget = static_cast<long>(o.evaluations_per_stroke * n);
  Improver improver(tour, near, nearest_to(tour.ends(), start_metric, o.neighbours));
  improver.run(budget, o.max_move_span);
  Improved out;
  out.order.reserve(static_cast<std::size_t>(n));
  for (int p = 0; p < n; ++p) {
    const int k = tour.stroke_at(p);
    out.order.emplace_back(order[k], tour.reversed(k));
  }
  out.length = tour.length();
  return out;
}

std::vector<std::pair<int, bool>> order_one_pen(const std::vector<Stroke>& all,
                                                const std::vector<int>& pen_members,
                                                const OrderOptions& o, const Vec2& start_metric) {
  const int n = static_cast<int>(pen_members.size());
  std::vector<Vec2> ends;
  const std::vector<int> members = members_by_cell(all, pen_members, o, ends);
  const NearLists near_by_stroke(ends, o.neighbours);
  std::vector<char> reversed(n, 0);
  std::vector<int> order = greedy_order(ends, start_metric, near_by_stroke, reversed);
  Improved best = improve(ends, order, reversed, near_by_stroke, o, start_metric);
  if (n <= kBothStartsMax) {
    // Drawings with structure (hatching, glyphs) sometimes suit the nearest-neighbour start
    // better; for small pens both are cheap, so both are tried and the shorter kept.
    order = nearest_neighbour_order(ends, start_metric, reversed);
    Improved nn = improve(ends, order, reversed, near_by_stroke, o, start_metric);
    if (nn.length < best.length) best = std::move(nn);
  }
  std::vector<std::pair<int, bool>> out;
  out.reserve(static_cast<std::size_t>(n));
  for (const auto& [s, turned] : best.order) {
    const std::size_t i = static_cast<std::size_t>(members[s]);
    out.emplace_back(members[s], turned && all[i].reversible);
  }
  return out;
}

}  // namespace

std::vector<Stroke> merge_touching(const std::vector<Stroke>& strokes, double join_mm) {
  const int n = static_cast<int>(strokes.size());
  std::vector<Vec2> ends(2 * n);
  for (int s = 0; s < n; ++s) {
    ends[2 * s] = strokes[s].start_mm;
    ends[2 * s + 1] = strokes[s].end_mm();
  }
  PointGrid grid(ends);
  std::vector<char> used(n, 0), reversible(n);
  std::vector<int> tools(n);  // read per candidate: kept apart from the strokes' bulk
  for (int s = 0; s < n; ++s) {
    tools[s] = strokes[s].tool;
    reversible[s] = strokes[s].reversible ? 1 : 0;
  }
  std::vector<Stroke> out;
  const auto find = [&](const Vec2& at, int tool) {
    const int e = grid.nearest_within(at, join_mm, [&](int id) {
      const int s = id / 2;
      return !used[s] && tools[s] == tool && (id % 2 == 0 || reversible[s]);
    });
    return (e >= 0 && (ends[e] - at).norm() <= join_mm) ? e : -1;
  };
  const auto use = [&](int s) {
    used[s] = 1;
    grid.forget(2 * s);
    grid.forget(2 * s + 1);
  };
  for (int s = 0; s < n; ++s) {
    if (used[s]) continue;
    use(s);
    Stroke chain = strokes[s];
    // Extend forward, then (reversible chains) backward by extending the reversed chain.
    for (int pass = 0; pass < (chain.reversible ? 2 : 1); ++pass) {
      if (pass == 1) turn_round(chain);
      for (int e = find(chain.end_mm(), chain.tool); e >= 0; e = find(chain.end_mm(), chain.tool)) {
        use(e / 2);
        const Stroke& next = strokes[e / 2];
        chain = joined(std::move(chain), e % 2 == 0 ? next : slicer::reversed(next));
        chain.reversible = chain.reversible && next.reversible;
      }
    }
    out.push_back(std::move(chain));
  }
  return out;
}

std::vector<Stroke> order_strokes(const std::vector<Stroke>& strokes, const OrderOptions& o) {
  std::map<int, std::vector<int>> by_tool;  // indices: strokes are copied once, into out
  for (std::size_t i = 0; i < strokes.size(); ++i) by_tool[strokes[i].tool].push_back(static_cast<int>(i));
  std::vector<Stroke> out;
  out.reserve(strokes.size());
  Vec2 at = o.start_mm;
  for (const auto& [tool, group] : by_tool) {
    for (const auto& [i, flip] : order_one_pen(strokes, group, o, o.metric ? o.metric(at) : at)) {
      out.push_back(strokes[static_cast<std::size_t>(i)]);
      if (flip) turn_round(out.back());
    }
    at = out.back().end_mm();
  }
  return out;
}

std::pair<double, double> pen_up_travel(const std::vector<Stroke>& strokes, const Vec2& start,
                                        const MetricMap& metric) {
  double paper = 0.0, axes = 0.0;
  Vec2 at = start;
  for (const auto& s : strokes) {
    paper += (s.start_mm - at).norm();
    axes += metric ? (metric(s.start_mm) - metric(at)).norm() : (s.start_mm - at).norm();
    at = s.end_mm();
  }
  return {paper, axes};
}

}  // namespace strand::post
