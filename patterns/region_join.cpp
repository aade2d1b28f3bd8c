// Piece ends as vertices on the rings; chains grown along ring neighbours, then merged.
#include "patterns/region_join.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "patterns/join_search.h"

namespace strand::patterns {

using slicer::Vec2;

namespace {

// End e of piece p is vertex 2p + e (e = 0 start, 1 end).
struct EndGraph {
  std::vector<int> next, prev;   // ring neighbours of each vertex (-1 = none)
  std::vector<double> gap_next;  // ring distance from the vertex forward to next
};

EndGraph end_graph(const RingSet& rs, const std::vector<FillPiece>& pieces) {
  const int n = static_cast<int>(pieces.size()) * 2;
  EndGraph g{std::vector<int>(n, -1), std::vector<int>(n, -1), std::vector<double>(n, 0.0)};
  std::vector<std::vector<int>> on_ring(rs.rings.size());
  auto spot = [&](int v) { return v % 2 == 0 ? pieces[v / 2].start : pieces[v / 2].end; };
  for (int v = 0; v < n; ++v) {
    if (spot(v).ring >= 0) on_ring[static_cast<std::size_t>(spot(v).ring)].push_back(v);
  }
  for (auto& vs : on_ring) {
    std::sort(vs.begin(), vs.end(), [&](int a, int b) {
      return spot(a).s_mm != spot(b).s_mm ? spot(a).s_mm < spot(b).s_mm : a < b;
    });
    for (std::size_t i = 0; i < vs.size() && vs.size() > 1; ++i) {
      const int a = vs[i], b = vs[(i + 1) % vs.size()];
      g.next[a] = b;
      g.prev[b] = a;
      g.gap_next[a] = ring_gap(rs, spot(a), spot(b));
    }
  }
  return g;
}

// One chain step: piece `piece` walked reversed or not; the ring stretch before it walks
// the ring forward (increasing s) or backward.
struct Step {
  int piece = 0;
  bool reversed = false;
  bool join_forward = true;
};
using Chain = std::vector<Step>;

int head_vertex(const Step& s) { return 2 * s.piece + (s.reversed ? 1 : 0); }
int tail_vertex(const Step& s) { return 2 * s.piece + (s.reversed ? 0 : 1); }

Chain reversed_chain(const Chain& c) {
  Chain r;
  for (std::size_t i = c.size(); i-- > 0;) {
    Step s = c[i];
    s.reversed = !s.reversed;
    // The stretch into the new step i came out of old step i + 1, walked the other way.
    s.join_forward = i + 1 < c.size() ? !c[i + 1].join_forward : true;
    r.push_back(s);
  }
  return r;
}

class Joiner {
 public:
  // How a run grows its chains: pieces in their order or reversed, started at the beginning
  // or a quarter, half or three quarters in; at each end the shorter ring stretch, or
  // always the stretch forward along the ring, or always backward.
  enum class Prefer { Shorter, Forward, Backward };
  static constexpr int kVariants = 24;

  Joiner(const RingSet& rs, const std::vector<FillPiece>& pieces)
      : pieces_(pieces), g_(end_graph(rs, pieces)) {}

  // Variant v: order reversed when v is odd, preference (v / 2) % 3, start (v / 6) / 4 in.
  std::vector<Chain> run(int variant) {
    used_.assign(pieces_.size(), false);
    prefer_ = static_cast<Prefer>((variant / 2) % 3);
    std::vector<int> order(pieces_.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return pieces_[a].line.order < pieces_[b].line.order; });
    if (variant % 2 == 1) std::reverse(order.begin(), order.end());
    // Variants 6 and up start a quarter, half or three quarters into the order.
    std::rotate(order.begin(),
                order.begin() + static_cast<std::ptrdiff_t>(order.size() * (variant / 6) / 4),
                order.end());
    std::vector<Chain> chains;
    for (int p : order) {
      if (used_[p]) continue;
      used_[p] = true;
      Chain c{{p, false, true}};
      grow(c);
      c = reversed_chain(c);
      grow(c);
      chains.push_back(reversed_chain(c));
    }
    chains = merge(std::move(chains));
    for (std::size_t round = 0; round < pieces_.size() && chains.size() > 1; ++round) {
      const std::size_t before = chains.size();
      if (!swap_once(chains)) break;
      chains = merge(std::move(chains));
      if (chains.size() >= before) break;
    }
    return chains;
  }

 private:
  // Extends the chain at its tail while a ring neighbour of the tail starts a free piece.
  void grow(Chain& c) {
    for (;;) {
      const int v = tail_vertex(c.back());
      int best = -1;
      bool forward = true;
      double best_gap = 0.0;
      for (bool fwd : {true, false}) {
        const int w = fwd ? g_.next[v] : g_.prev[v];
        if (w < 0 || used_[w / 2]) continue;
        const double gap = fwd ? g_.gap_next[v] : g_.gap_next[w];
        const bool wanted =
            prefer_ == Prefer::Shorter ? gap < best_gap : fwd == (prefer_ == Prefer::Forward);
        if (best < 0 || wanted) best = w, forward = fwd, best_gap = gap;
      }
      if (best < 0) return;
      used_[best / 2] = true;
      c.push_back({best / 2, best % 2 == 1, forward});
    }
  }

  // Joins chain ends that are ring neighbours, shortest stretch first (union by chain id).
  std::vector<Chain> merge(std::vector<Chain> chains) {
    std::vector<int> chain_of(pieces_.size() * 2, -1);
    auto mark = [&](int id) {
      chain_of[head_vertex(chains[id].front())] = id;
      chain_of[tail_vertex(chains[id].back())] = id;
    };
    for (int i = 0; i < static_cast<int>(chains.size()); ++i) mark(i);
    struct Candidate {
      double gap;
      int from, to;  // from -> to walks the ring forward
    };
    std::vector<Candidate> cands;
    for (int v = 0; v < static_cast<int>(g_.next.size()); ++v) {
      if (g_.next[v] >= 0 && g_.next[v] != v) cands.push_back({g_.gap_next[v], v, g_.next[v]});
    }
    std::stable_sort(cands.begin(), cands.end(),
                     [](const Candidate& a, const Candidate& b) { return a.gap < b.gap; });
    for (const Candidate& k : cands) {
      const int a = chain_of[k.from], b = chain_of[k.to];
      if (a < 0 || b < 0 || a == b) continue;
      Chain ca = chains[a], cb = chains[b];
      if (head_vertex(ca.front()) == k.from) ca = reversed_chain(ca);  // k.from at the tail
      if (tail_vertex(cb.back()) == k.to) cb = reversed_chain(cb);     // k.to at the head
      if (tail_vertex(ca.back()) != k.from || head_vertex(cb.front()) != k.to) continue;
      cb.front().join_forward = true;
      chain_of[k.from] = chain_of[k.to] = -1;
      ca.insert(ca.end(), cb.begin(), cb.end());
      chains[a] = std::move(ca);
      chains[b].clear();
      mark(a);
    }
    std::vector<Chain> out;
    for (auto& c : chains) {
      if (!c.empty()) out.push_back(std::move(c));
    }
    return out;
  }

  // One exchange that frees a mergeable end: a strand end v whose ring neighbour w sits
  // inside another strand B, joined there to x. Dropping the stretch w-x and adding v-w
  // keeps the count, but frees x; when x has a ring neighbour that is the end of a third
  // strand (or of v's), the next merge joins them. Returns false when none exists.
  bool swap_once(std::vector<Chain>& chains) {
    std::vector<int> owner(pieces_.size() * 2, -1), at(pieces_.size() * 2, -1);
    for (int c = 0; c < static_cast<int>(chains.size()); ++c) {
      for (int k = 0; k < static_cast<int>(chains[c].size()); ++k) {
        owner[head_vertex(chains[c][k])] = owner[tail_vertex(chains[c][k])] = c;
        at[head_vertex(chains[c][k])] = at[tail_vertex(chains[c][k])] = k;
      }
    }
    auto is_end = [&](int v) {
      const Chain& c = chains[owner[v]];
      return v == head_vertex(c.front()) || v == tail_vertex(c.back());
    };
    for (int a = 0; a < static_cast<int>(chains.size()); ++a) {
      for (const int v : {head_vertex(chains[a].front()), tail_vertex(chains[a].back())}) {
        for (const int w : {g_.next[v], g_.prev[v]}) {
          if (w < 0 || owner[w] == a || is_end(w)) continue;
          const int b = owner[w];
          const int k = at[w];
          const bool w_is_head = w == head_vertex(chains[b][k]);
          const int x = w_is_head ? tail_vertex(chains[b][k - 1]) : head_vertex(chains[b][k + 1]);
          bool useful = false;
          for (const int y : {g_.next[x], g_.prev[x]}) {
            useful = useful || (y >= 0 && y != v && y != w && is_end(y));
          }
          if (!useful) continue;
          Chain b1(chains[b].begin() + (w_is_head ? k : 0),
                   chains[b].begin() + (w_is_head ? chains[b].size() : k + 1));
          Chain b2(chains[b].begin() + (w_is_head ? 0 : k + 1),
                   chains[b].begin() + (w_is_head ? k : chains[b].size()));
          Chain ca = chains[a];
          if (head_vertex(ca.front()) == v) ca = reversed_chain(ca);
          if (tail_vertex(b1.back()) == w) b1 = reversed_chain(b1);
          b1.front().join_forward = g_.next[v] == w;
          ca.insert(ca.end(), b1.begin(), b1.end());
          chains[a] = std::move(ca);
          chains[b] = std::move(b2);
          return true;
        }
      }
    }
    return false;
  }

  const std::vector<FillPiece>& pieces_;
  EndGraph g_;
  std::vector<bool> used_;
  Prefer prefer_ = Prefer::Shorter;
};

// Deposited length of the ring stretches a set of chains uses.
double join_length(const EndGraph& g, const std::vector<Chain>& chains) {
  double len = 0.0;
  for (const Chain& c : chains) {
    for (std::size_t k = 1; k < c.size(); ++k) {
      const int a = tail_vertex(c[k - 1]), b = head_vertex(c[k]);
      len += c[k].join_forward ? g.gap_next[a] : g.gap_next[b];
    }
  }
  return len;
}

RingSpot spot_of(const std::vector<FillPiece>& pieces, int v) {
  return v % 2 == 0 ? pieces[v / 2].start : pieces[v / 2].end;
}

slicer::Stroke emit(const RingSet& rs, const std::vector<FillPiece>& pieces, const Chain& c,
                    const JoinOptions& o) {
  slicer::Stroke s;
  s.width_mm = o.width_mm;
  s.height_mm = o.height_mm;
  for (std::size_t k = 0; k < c.size(); ++k) {
    const Step& st = c[k];
    const PatternLine& line = pieces[static_cast<std::size_t>(st.piece)].line;
    std::vector<Vec2> pts = line.points;
    std::vector<slicer::Feature> feats = line.features;
    if (st.reversed) {
      std::reverse(pts.begin(), pts.end());
      std::reverse(feats.begin(), feats.end());
    }
    if (k == 0) {
      s.start_mm = pts.front();
    } else {
      std::vector<Vec2> join;
      walk_ring(rs, spot_of(pieces, tail_vertex(c[k - 1])), spot_of(pieces, head_vertex(st)),
                st.join_forward, join);
      for (const Vec2& q : join) s.segments.push_back(slicer::line_to(q, o.connector));
    }
    for (std::size_t i = 1; i < pts.size(); ++i)
      s.segments.push_back(slicer::line_to(pts[i], feats[i - 1]));
  }
  return s;
}

// The loop beside each vertex: the nearest within 1.05 bead widths, as perimeter_splice
// takes it (the fill boundary lies one bead inside the innermost perimeter; where holes
// merge with each other or the outside at that depth, one ring runs beside several loops).
std::vector<int> loop_of_vertices(const RingSet& rs, const std::vector<FillPiece>& pieces,
                                  const std::vector<slicer::Stroke>& loops, double width_mm) {
  const double reach = 1.05 * width_mm;
  std::vector<std::pair<Vec2, Vec2>> boxes;
  for (const slicer::Stroke& l : loops) {
    Vec2 lo = l.start_mm, hi = l.start_mm;
    for (const auto& seg : l.segments) lo = lo.cwiseMin(seg.end_mm), hi = hi.cwiseMax(seg.end_mm);
    boxes.emplace_back(lo - Vec2(reach, reach), hi + Vec2(reach, reach));
  }
  std::vector<int> out(pieces.size() * 2, -1);
  for (std::size_t v = 0; v < out.size(); ++v) {
    const RingSpot spot = spot_of(pieces, static_cast<int>(v));
    if (spot.ring < 0) continue;
    const Vec2 q = point_at(rs, spot);
    double best = reach;
    for (std::size_t l = 0; l < loops.size(); ++l) {
      if ((q.array() < boxes[l].first.array()).any() || (q.array() > boxes[l].second.array()).any())
        continue;
      Vec2 at = loops[l].start_mm;
      for (const auto& seg : loops[l].segments) {
        const double dist = slicer::point_segment_distance(q, at, seg.end_mm);
        if (dist < best) best = dist, out[v] = static_cast<int>(l);
        at = seg.end_mm;
      }
    }
  }
  return out;
}

std::vector<int> mates_of(const std::vector<Chain>& chains, std::size_t vertices) {
  std::vector<int> mate(vertices, -1);
  for (const Chain& c : chains) {
    for (std::size_t k = 1; k < c.size(); ++k) {
      mate[tail_vertex(c[k - 1])] = head_vertex(c[k]);
      mate[head_vertex(c[k])] = tail_vertex(c[k - 1]);
    }
  }
  return mate;
}

// Chains walked from each strand end in index order; a join runs the shorter way round when
// both ways reach the neighbour (a ring with two ends).
std::vector<Chain> chains_of(const EndGraph& g, const std::vector<int>& mate) {
  std::vector<Chain> out;
  std::vector<bool> done(mate.size(), false);
  for (int v = 0; v < static_cast<int>(mate.size()); ++v) {
    if (mate[v] >= 0 || done[v]) continue;
    Chain c{{v / 2, v % 2 == 1, true}};
    for (int u = v ^ 1; mate[u] >= 0; u = mate[u] ^ 1) {
      const int w = mate[u];
      const bool forward =
          g.next[u] == w && (g.prev[u] != w || g.gap_next[u] <= g.gap_next[w]);
      c.push_back({w / 2, w % 2 == 1, forward});
    }
    done[v] = done[tail_vertex(c.back())] = true;
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace

std::vector<slicer::Stroke> join_pieces(const RingSet& rs, const std::vector<FillPiece>& pieces,
                                        const JoinOptions& options,
                                        const std::vector<slicer::Stroke>& loops) {
  // Every growth variant is tried; the fewest strands win, then the least ring deposited.
  Joiner joiner(rs, pieces);
  const EndGraph g = end_graph(rs, pieces);
  std::vector<Chain> best;
  double best_len = 0.0;
  for (int v = 0; v < Joiner::kVariants; ++v) {
    std::vector<Chain> chains = joiner.run(v);
    const double len = join_length(g, chains);
    if (v == 0 || chains.size() < best.size() ||
        (chains.size() == best.size() && len < best_len - 1e-9)) {
      best = std::move(chains);
      best_len = len;
    }
  }
  const JoinGraph jg{g.next, g.prev, loop_of_vertices(rs, pieces, loops, options.width_mm),
                     static_cast<int>(loops.size())};
  std::vector<int> mate = mates_of(best, g.next.size());
  const int before = join_score(jg, mate);
  improve_joins(jg, mate);
  if (join_score(jg, mate) < before) best = chains_of(g, mate);  // else the variant as it was
  std::vector<slicer::Stroke> out;
  for (const Chain& c : best) out.push_back(emit(rs, pieces, c, options));
  return out;
}

}  // namespace strand::patterns
