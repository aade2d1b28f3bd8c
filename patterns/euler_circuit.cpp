// Non-crossing Euler circuits: pair neighbouring ends at every vertex, then switch a
// vertex to its other neighbour pairing whenever that joins curves, until one is left:
// first the switches sure to join (a linear sweep with union-find), then trial switches
// checked by walking the curves.
#include "patterns/euler_circuit.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>

namespace strand::patterns {

int PlaneGraph::add_edge(int from, int to, double a_from, double a_to) {
  edge_from.push_back(from);
  edge_to.push_back(to);
  angle_from_rad.push_back(a_from);
  angle_to_rad.push_back(a_to);
  return static_cast<int>(edge_from.size()) - 1;
}

namespace {

// End id = 2 * edge + side (side 0 at edge_from, 1 at edge_to).
class Pairing {
 public:
  explicit Pairing(const PlaneGraph& g) : ends_(static_cast<std::size_t>(g.vertex_count)) {
    const int edges = static_cast<int>(g.edge_from.size());
    pos_.resize(static_cast<std::size_t>(2 * edges));
    vertex_.resize(pos_.size());
    for (int e = 0; e < edges; ++e) {
      ends_[static_cast<std::size_t>(g.edge_from[static_cast<std::size_t>(e)])].push_back(2 * e);
      ends_[static_cast<std::size_t>(g.edge_to[static_cast<std::size_t>(e)])].push_back(2 * e + 1);
    }
    for (std::size_t v = 0; v < ends_.size(); ++v) {
      auto angle = [&](int end) {
        const auto e = static_cast<std::size_t>(end / 2);
        return end % 2 == 0 ? g.angle_from_rad[e] : g.angle_to_rad[e];
      };
      auto& list = ends_[v];
      if (list.size() % 2 != 0) throw std::logic_error("noncrossing_circuits: odd vertex degree");
      std::sort(list.begin(), list.end(),
                [&](int a, int b) { return angle(a) != angle(b) ? angle(a) < angle(b) : a < b; });
      for (std::size_t k = 0; k < list.size(); ++k) {
        pos_[static_cast<std::size_t>(list[k])] = static_cast<int>(k);
        vertex_[static_cast<std::size_t>(list[k])] = static_cast<int>(v);
      }
    }
    offset_.assign(ends_.size(), 0);
    frozen_.assign(ends_.size(), false);
    for (std::size_t v = 0; v < ends_.size(); ++v) {
      const auto& list = ends_[v];
      for (std::size_t k = 0; k < list.size() && list.size() > 2; ++k) {
        if (list[k] / 2 != list[(k + 1) % list.size()] / 2) continue;
        offset_[v] = static_cast<int>((k + 1) % 2);  // never pair a loop's two ends
        frozen_[v] = true;
      }
    }
  }

  int partner(int end) const {
    const auto v = static_cast<std::size_t>(vertex_[static_cast<std::size_t>(end)]);
    const int k = static_cast<int>(ends_[v].size());
    const int p = pos_[static_cast<std::size_t>(end)];
    const int q = ((p - offset_[v] + k) % k) % 2 == 0 ? p + 1 : p - 1;
    return ends_[v][static_cast<std::size_t>((q + k) % k)];
  }
  std::size_t degree(std::size_t v) const { return ends_[v].size(); }
  // Vertices of degree >= 4 whose pairing may change.
  bool flippable(std::size_t v) const { return ends_[v].size() >= 4 && !frozen_[v]; }
  void flip(std::size_t v) { offset_[v] ^= 1; }
  // The first end of pass m (0 <= m < degree / 2) at v under the current pairing.
  int pass_end(std::size_t v, std::size_t m) const {
    return ends_[v][(static_cast<std::size_t>(offset_[v]) + 2 * m) % ends_[v].size()];
  }
  int vertex_count() const { return static_cast<int>(ends_.size()); }
  const std::vector<int>& ends(std::size_t v) const { return ends_[v]; }

 private:
  std::vector<std::vector<int>> ends_;  // per vertex, sorted by angle
  std::vector<int> pos_, vertex_;       // per end
  std::vector<int> offset_;             // per vertex: pairs (o + 2m, o + 2m + 1)
  // Per vertex: holds a loop (an edge leaving and returning to it, e.g. a grip band round a
  // cylinder) whose ends are neighbours. Pairing them would close the loop on itself, and
  // the face between the loop and the vertex's other edges touches the vertex on both sides,
  // so only the other pairing can join the loop into the strand: it is fixed.
  std::vector<bool> frozen_;
};

// Walks every curve; `label` gets the curve index of each edge.
std::vector<std::vector<CircuitStep>> walk(const Pairing& p, int edges, std::vector<int>& label) {
  std::vector<std::vector<CircuitStep>> curves;
  label.assign(static_cast<std::size_t>(edges), -1);
  for (int start = 0; start < edges; ++start) {
    if (label[static_cast<std::size_t>(start)] >= 0) continue;
    std::vector<CircuitStep> c;
    int end = 2 * start;  // leave through the edge's from-end
    while (true) {
      const int e = end / 2;
      if (label[static_cast<std::size_t>(e)] >= 0) break;
      label[static_cast<std::size_t>(e)] = static_cast<int>(curves.size());
      c.push_back({e, end % 2 == 0});
      end = p.partner(end ^ 1);  // arrive at the far end, continue with its partner
    }
    curves.push_back(std::move(c));
  }
  return curves;
}

// The current curves and the curve of every edge.
struct Curves {
  std::vector<std::vector<CircuitStep>> list;
  std::vector<int> label;
};

bool mixed(const Pairing& p, const Curves& c, std::size_t v) {
  const auto& ends = p.ends(v);
  return std::any_of(ends.begin(), ends.end(), [&](int end) {
    return c.label[static_cast<std::size_t>(end / 2)] !=
           c.label[static_cast<std::size_t>(ends[0] / 2)];
  });
}

// Flips `vs` and keeps the result when it has fewer curves; else flips them back.
bool try_flips(Pairing& p, int edges, Curves& c, std::initializer_list<std::size_t> vs) {
  for (std::size_t v : vs) p.flip(v);
  Curves trial;
  trial.list = walk(p, edges, trial.label);
  if (trial.list.size() < c.list.size()) {
    c = std::move(trial);
    return true;
  }
  for (std::size_t v : vs) p.flip(v);
  return false;
}

int find_root(std::vector<int>& parent, int x) {
  while (parent[static_cast<std::size_t>(x)] != x) {
    x = parent[static_cast<std::size_t>(x)] =
        parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
  }
  return x;
}

// The linear first sweep: at a vertex whose passes all lie on different curves, the other
// neighbour pairing joins them into one (leave by the end after a pass, and each curve leads
// round to the next pass), so flip it without walking; union-find follows the merges. Only
// such sure merges are made, so the labels stay exact. Returns whether anything flipped.
bool sure_merges(Pairing& p, Curves& c) {
  std::vector<int> parent(c.list.size());
  std::iota(parent.begin(), parent.end(), 0);
  bool flipped = false;
  for (std::size_t v = 0; v < static_cast<std::size_t>(p.vertex_count()); ++v) {
    if (!p.flippable(v)) continue;
    std::vector<int> roots;
    for (std::size_t m = 0; m < p.degree(v) / 2; ++m) {
      roots.push_back(find_root(parent, c.label[static_cast<std::size_t>(p.pass_end(v, m) / 2)]));
    }
    std::vector<int> sorted = roots;
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) continue;
    p.flip(v);
    for (int r : roots) parent[static_cast<std::size_t>(r)] = roots[0];
    flipped = true;
  }
  return flipped;
}

// One sweep of single flips at vertices where curves meet; true when any merged curves.
bool single_flips(Pairing& p, int edges, Curves& c) {
  bool improved = false;
  const auto n = static_cast<std::size_t>(p.vertex_count());
  for (std::size_t v = 0; v < n && c.list.size() > 1; ++v) {
    if (p.flippable(v) && mixed(p, c, v)) improved |= try_flips(p, edges, c, {v});
  }
  return improved;
}

// Out of a local minimum (a degree-6 flip changes three pairings at once, so it can join two
// curves only together with a change nearby): a vertex where curves meet flipped together
// with one of its neighbours; stops at the first pair that merges curves.
bool pair_flips(Pairing& p, const PlaneGraph& g, int edges, Curves& c) {
  for (std::size_t v = 0; v < static_cast<std::size_t>(p.vertex_count()); ++v) {
    if (!p.flippable(v) || !mixed(p, c, v)) continue;
    for (int end : p.ends(v)) {
      const auto e = static_cast<std::size_t>(end / 2);
      const auto u = static_cast<std::size_t>(end % 2 == 0 ? g.edge_to[e] : g.edge_from[e]);
      if (u != v && p.flippable(u) && try_flips(p, edges, c, {v, u})) return true;
    }
  }
  return false;
}

}  // namespace

std::vector<std::vector<CircuitStep>> noncrossing_circuits(const PlaneGraph& g) {
  Pairing p(g);
  const int edges = static_cast<int>(g.edge_from.size());
  Curves c;
  c.list = walk(p, edges, c.label);
  if (c.list.size() > 1 && sure_merges(p, c)) c.list = walk(p, edges, c.label);
  while (c.list.size() > 1) {
    if (!single_flips(p, edges, c) && !pair_flips(p, g, edges, c)) break;
  }
  return std::move(c.list);
}

}  // namespace strand::patterns
