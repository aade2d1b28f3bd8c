// Stroke merging, nearest-neighbour tours and 2-opt / Or-opt improvement.
#include "postprocess/plot/stroke_ordering.h"

#include <algorithm>
#include <map>
#include <memory>

#include "postprocess/plot/point_grid.h"

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

// Open path over strokes with a fixed start point; every stroke is costed as reversible and
// non-reversible ones are simply not flipped in the result (plotting strokes all reverse).
// Open path over reversible strokes with a fixed start point. Endpoint 2s is the start of
// stroke s, 2s + 1 its end.
class Tour {
 public:
  // Strokes 0..n-1 in this order (labels follow the starting tour, so the positions a
  // reversal touches sit close together in memory), `reversed` giving each one's way round.
  Tour(std::vector<Vec2> ends, const Vec2& start, const std::vector<char>& reversed)
      : ends_(std::move(ends)), start_(start), order_(ends_.size() / 2), pos_(ends_.size() / 2) {
    for (int p = 0; p < size(); ++p) {
      order_[p] = 2 * p + (reversed[p] ? 1 : 0);
      pos_[p] = p;
    }
  }
  int size() const { return static_cast<int>(order_.size()); }
  // Entries are 2 * stroke + 1 when the stroke is drawn turned round: its entry endpoint.
  int stroke_at(int p) const { return order_[p] >> 1; }
  int in(int p) const { return order_[p]; }
  int out(int p) const { return order_[p] ^ 1; }
  Vec2 out_point(int p) const { return p < 0 ? start_ : ends_[out(p)]; }
  Vec2 in_point(int p) const { return ends_[in(p)]; }
  // Cost of the edge from position p to p + 1 (p = -1: from the start; p + 1 = size: none).
  double edge(int p) const {
    if (p + 1 >= size()) return 0.0;
    return (out_point(p) - in_point(p + 1)).norm();
  }
  double d(const Vec2& a, const Vec2& b) const { return (a - b).norm(); }
  Vec2 ends_point(int e) const { return ends_[e]; }
  // Reverses positions i..j and turns each of those strokes round, in one pass.
  void reverse_block(int i, int j) {
    for (int a = i, b = j; a <= b; ++a, --b) {
      const int oa = order_[a] ^ 1, ob = order_[b] ^ 1;
      order_[a] = ob;
      order_[b] = oa;
      pos_[ob >> 1] = a;
      pos_[oa >> 1] = b;
    }
  }
  // Moves the stroke at position m to position to, keeping its direction; the strokes
  // between shift by one.
  void shift(int m, int to) {
    const int o = order_[m];
    if (to > m) {
      for (int k = m; k < to; ++k) pos_[(order_[k] = order_[k + 1]) >> 1] = k;
    } else {
      for (int k = m; k > to; --k) pos_[(order_[k] = order_[k - 1]) >> 1] = k;
    }
    order_[to] = o;
    pos_[o >> 1] = to;
  }
  int pos_of(int stroke) const { return pos_[stroke]; }
  const std::vector<Vec2>& ends() const { return ends_; }
  bool reversed(int stroke) const { return (order_[pos_[stroke]] & 1) != 0; }
  double length() const {
    double total = 0.0;
    for (int p = -1; p + 1 < size(); ++p) total += edge(p);
    return total;
  }

 private:
  std::vector<Vec2> ends_;
  Vec2 start_;
  std::vector<int> order_;  // per position: 2 * stroke + turned round
  std::vector<int> pos_;    // per stroke: its position
};

std::vector<int> nearest_neighbour_order(const std::vector<Vec2>& ends, const Vec2& start,
                                         std::vector<char>& reversed) {
  const int n = static_cast<int>(ends.size() / 2);
  auto grid = std::make_unique<PointGrid>(ends);
  int grid_size = n;  // strokes alive when the grid was built
  std::vector<char> used(n, 0);
  std::vector<int> order;
  order.reserve(n);
  Vec2 at = start;
  for (int k = 0; k < n; ++k) {
    // Rebuild over the remaining ends when three quarters are gone: keeps each search local
    // and the total rebuild cost linear (n + n/4 + n/16 + ...).
    if (n - k < grid_size / 4 && n - k > 64) {
      std::vector<int> alive;
      for (int s = 0; s < n; ++s) {
        if (!used[s]) alive.insert(alive.end(), {2 * s, 2 * s + 1});
      }
      grid = std::make_unique<PointGrid>(ends, alive);
      grid_size = n - k;
    }
    const int e = grid->nearest(at, [&](int id) { return !used[id / 2]; });
    const int s = e / 2;
    used[s] = 1;
    grid->forget(2 * s);
    grid->forget(2 * s + 1);
    reversed[s] = (e % 2 == 1);
    order.push_back(s);
    at = ends[reversed[s] ? 2 * s : 2 * s + 1];
  }
  return order;
}

// Candidate lists, flat: the k nearest other endpoints of endpoint e, nearest first.
class NearLists {
 public:
  NearLists(const std::vector<Vec2>& ends, int k) : k_(std::clamp(k, 0, PointGrid::kMaxK)) {
    PointGrid grid(ends);
    ids_.resize(ends.size() * static_cast<std::size_t>(k_));
    count_.resize(ends.size());
    for (std::size_t e = 0; e < ends.size(); ++e) {
      const int s = static_cast<int>(e / 2);
      count_[e] = static_cast<std::uint8_t>(
          grid.k_nearest(ends[e], k_, [s](int id) { return id / 2 == s; }, &ids_[e * k_]));
    }
  }
  struct Range {
    const int* b;
    const int* e;
    const int* begin() const { return b; }
    const int* end() const { return e; }
  };
  Range operator[](int e) const {
    const int* b = ids_.data() + static_cast<std::size_t>(e) * k_;
    return {b, b + count_[static_cast<std::size_t>(e)]};
  }

 private:
  int k_;
  std::vector<int> ids_;
  std::vector<std::uint8_t> count_;
};

// 2-opt and Or-opt driven by candidate lists: for the edge a -> b leaving position p, try
// joining a to one of its near endpoints instead, or b to one of its own; move single
// strokes (either way round) next to a near endpoint.
class Improver {
 public:
  Improver(Tour& t, const NearLists& near, const OrderOptions& o) : t_(t), near_(near), o_(o) {}

  void run(long budget) {
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
            try_or_opt(edge_at, budget)) {
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

  bool try_two_opt(int p, long& budget) {
    if (p < 0) return false;
    const Vec2 a = t_.out_point(p), b = t_.in_point(p + 1);
    const double ab = t_.d(a, b);
    for (int c : near_[t_.out(p)]) {
      --budget;
      const Vec2 cp = t_.ends_point(c);
      const double ac = t_.d(a, cp);
      if (ac >= ab) break;
      const int q = t_.pos_of(c / 2);
      if (q > p && c == t_.out(q) && q - p <= o_.max_move_span) {
        // reverse [p+1 .. q]: a -> out(q), in(p+1) -> in(q+1)
        const double next = q + 1 < t_.size() ? t_.d(b, t_.in_point(q + 1)) - t_.edge(q) : -t_.edge(q);
        if (ac + next - ab < -1e-9) {
          apply_reverse(p + 1, q);
          return true;
        }
      } else if (q <= p && c == t_.in(q) && p - q <= o_.max_move_span) {
        // reverse [q .. p]: out(q-1) -> out(p) = a, in(q) = c -> b
        const Vec2 prev = t_.out_point(q - 1);
        const double delta = t_.d(prev, a) + t_.d(cp, b) - t_.d(prev, cp) - ab;
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
    const double ab = t_.d(a, b);
    for (int c : near_[t_.in(p + 1)]) {
      --budget;
      const Vec2 cp = t_.ends_point(c);
      const double bc = t_.d(b, cp);
      if (bc >= ab) break;
      const int q = t_.pos_of(c / 2);
      if (q > p + 1 && c == t_.in(q) && q - 1 - p <= o_.max_move_span) {
        // reverse [p+1 .. q-1]: a -> out(q-1), in(p+1) = b -> c = in(q)
        const Vec2 d = t_.out_point(q - 1);
        const double delta = t_.d(a, d) + bc - ab - t_.d(d, cp);
        if (delta < -1e-9) {
          apply_reverse(p + 1, q - 1);
          return true;
        }
      } else if (q <= p && c == t_.in(q) && p - q <= o_.max_move_span) {
        // reverse [q .. p]: out(q-1) -> out(p) = a, c = in(q) -> b
        const Vec2 prev = t_.out_point(q - 1);
        const double delta = t_.d(prev, a) + bc - t_.d(prev, cp) - ab;
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
    const double removed = t_.d(prev, in_m) + (last ? 0.0 : t_.d(out_m, t_.in_point(m + 1)) -
                                                          t_.d(prev, t_.in_point(m + 1)));
    for (int c : near_[t_.in(m)]) {
      --budget;
      const int q = t_.pos_of(c / 2);
      if (q == m || c != t_.out(q) || std::abs(q - m) > o_.max_move_span) continue;
      const Vec2 cp = t_.ends_point(c);
      const bool q_last = q + 1 >= t_.size();
      const Vec2 nxt = q_last ? Vec2::Zero() : t_.in_point(q + 1);
      if (q + 1 == m) continue;
      const double added = t_.d(cp, in_m) + (q_last ? 0.0 : t_.d(out_m, nxt) - t_.d(cp, nxt));
      if (added - removed < -1e-9) {
        move_after(m, q);
        return true;
      }
    }
    // The stroke turned round: out(q) -> out(m) ... in(m) -> in(q + 1).
    for (int c : near_[t_.out(m)]) {
      --budget;
      const int q = t_.pos_of(c / 2);
      if (q == m || q + 1 == m || c != t_.out(q) || std::abs(q - m) > o_.max_move_span) continue;
      const Vec2 cp = t_.ends_point(c);
      const bool q_last = q + 1 >= t_.size();
      const Vec2 nxt = q_last ? Vec2::Zero() : t_.in_point(q + 1);
      const double added = t_.d(cp, out_m) + (q_last ? 0.0 : t_.d(in_m, nxt) - t_.d(cp, nxt));
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

  Tour& t_;
  const NearLists& near_;
  const OrderOptions& o_;
  std::vector<int> touched_;
};

// One pen's strokes (indices into `all`) in drawing order, each with whether to turn it
// round; the strokes themselves are copied once, by order_strokes.
std::vector<std::pair<int, bool>> order_one_pen(const std::vector<Stroke>& all,
                                                const std::vector<int>& members,
                                                const OrderOptions& o, const Vec2& start_metric) {
  const int n = static_cast<int>(members.size());
  const auto stroke = [&](int s) -> const Stroke& { return all[static_cast<std::size_t>(members[s])]; };
  std::vector<Vec2> ends(2 * n);
  for (int s = 0; s < n; ++s) {
    ends[2 * s] = o.metric ? o.metric(stroke(s).start_mm) : stroke(s).start_mm;
    ends[2 * s + 1] = o.metric ? o.metric(stroke(s).end_mm()) : stroke(s).end_mm();
  }
  std::vector<char> reversed(n, 0);
  const std::vector<int> order = nearest_neighbour_order(ends, start_metric, reversed);
  // Strokes relabelled in tour order: label k is stroke order[k].
  std::vector<Vec2> tour_ends(ends.size());
  std::vector<char> tour_reversed(n, 0);
  for (int k = 0; k < n; ++k) {
    tour_ends[2 * k] = ends[2 * order[k]];
    tour_ends[2 * k + 1] = ends[2 * order[k] + 1];
    tour_reversed[k] = reversed[order[k]];
  }
  std::vector<Vec2>().swap(ends);
  Tour tour(std::move(tour_ends), start_metric, tour_reversed);
  const NearLists near(tour.ends(), o.neighbours);
  Improver(tour, near, o).run(static_cast<long>(o.evaluations_per_stroke * n));
  std::vector<std::pair<int, bool>> out;
  out.reserve(static_cast<std::size_t>(n));
  for (int p = 0; p < n; ++p) {
    const int k = tour.stroke_at(p);
    out.emplace_back(members[order[k]], tour.reversed(k) && stroke(order[k]).reversible);
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
  std::vector<char> used(n, 0);
  std::vector<Stroke> out;
  const auto find = [&](const Vec2& at, int tool) {
    const int e = grid.nearest_within(at, join_mm, [&](int id) {
      const int s = id / 2;
      return !used[s] && strokes[s].tool == tool && (id % 2 == 0 || strokes[s].reversible);
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
      if (pass == 1) chain = slicer::reversed(chain);
      for (int e = find(chain.end_mm(), chain.tool); e >= 0; e = find(chain.end_mm(), chain.tool)) {
        use(e / 2);
        const Stroke& next = strokes[e / 2];
        chain = joined(chain, e % 2 == 0 ? next : slicer::reversed(next));
        chain.reversible = chain.reversible && next.reversible;
      }
    }
    out.push_back(chain);
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
      out.push_back(flip ? slicer::reversed(strokes[static_cast<std::size_t>(i)]) : strokes[static_cast<std::size_t>(i)]);
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
