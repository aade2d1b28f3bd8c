// Non-crossing Euler circuits: pair neighbouring ends at every vertex, then switch a
// vertex to its other neighbour pairing whenever that joins curves, until one is left.
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
  }

  int partner(int end) const {
    const auto v = static_cast<std::size_t>(vertex_[static_cast<std::size_t>(end)]);
    const int k = static_cast<int>(ends_[v].size());
    const int p = pos_[static_cast<std::size_t>(end)];
    const int q = ((p - offset_[v] + k) % k) % 2 == 0 ? p + 1 : p - 1;
    return ends_[v][static_cast<std::size_t>((q + k) % k)];
  }
  std::size_t degree(std::size_t v) const { return ends_[v].size(); }
  void flip(std::size_t v) { offset_[v] ^= 1; }
  int vertex_count() const { return static_cast<int>(ends_.size()); }
  const std::vector<int>& ends(std::size_t v) const { return ends_[v]; }

 private:
  std::vector<std::vector<int>> ends_;  // per vertex, sorted by angle
  std::vector<int> pos_, vertex_;       // per end
  std::vector<int> offset_;             // per vertex: pairs (o + 2m, o + 2m + 1)
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

}  // namespace

std::vector<std::vector<CircuitStep>> noncrossing_circuits(const PlaneGraph& g) {
  Pairing p(g);
  const int edges = static_cast<int>(g.edge_from.size());
  std::vector<int> label;
  auto curves = walk(p, edges, label);
  bool improved = true;
  while (curves.size() > 1 && improved) {
    improved = false;
    for (std::size_t v = 0; v < static_cast<std::size_t>(p.vertex_count()); ++v) {
      if (p.degree(v) < 4) continue;
      const auto& ends = p.ends(v);
      const bool mixed = std::any_of(ends.begin(), ends.end(), [&](int end) {
        return label[static_cast<std::size_t>(end / 2)] !=
               label[static_cast<std::size_t>(ends[0] / 2)];
      });
      if (!mixed) continue;
      p.flip(v);
      std::vector<int> trial_label;
      auto trial = walk(p, edges, trial_label);
      if (trial.size() < curves.size()) {
        curves = std::move(trial);
        label = std::move(trial_label);
        improved = true;
      } else {
        p.flip(v);
      }
    }
  }
  return curves;
}

}  // namespace strand::patterns
