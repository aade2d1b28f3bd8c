// Start tours: greedy matching of stroke endpoints into chains walked nearest-first, and the
// plain nearest-neighbour walk.
#include "postprocess/plot/start_tour.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <memory>

#include "postprocess/plot/point_grid.h"

namespace strand::post {

namespace {

using slicer::Vec2;

// Candidate gaps taken per endpoint: the nearest few decide almost every greedy link.
constexpr int kGreedyCandidates = 8;
// Rounds over the chain ends left; each usually joins most chains, and whatever is left after
// the last is joined by the nearest-first walk (so no input makes the rounds quadratic).
constexpr int kMaxRounds = 32;

// Whether b is among the candidates of a that the greedy pass reads.
bool listed(const NearLists& near, int a, int b) {
  int taken = 0;
  for (int f : near[a]) {
    if (taken++ == kGreedyCandidates) break;
    if (f == b) return true;
  }
  return false;
}

// Candidate gaps a - b as (a, b), sorted by (length, place in `gaps`): the float's bits order
// as the length does (lengths are >= 0), the low half keeps the given order for ties.
std::vector<std::pair<int, int>> sorted(const std::vector<Vec2>& ends,
                                        std::vector<std::pair<int, int>> gaps) {
  std::vector<std::uint64_t> keys(gaps.size());
  for (std::size_t i = 0; i < gaps.size(); ++i) {
    const float d = static_cast<float>((ends[gaps[i].first] - ends[gaps[i].second]).norm());
    std::uint32_t bits;
    std::memcpy(&bits, &d, sizeof bits);
    keys[i] = static_cast<std::uint64_t>(bits) << 32 | i;
  }
  std::sort(keys.begin(), keys.end());
  std::vector<std::pair<int, int>> out(gaps.size());
  for (std::size_t i = 0; i < keys.size(); ++i) out[i] = gaps[keys[i] & 0xffffffffu];
  return out;
}

// The first round's gaps: each endpoint's nearest candidates, each gap once.
std::vector<std::pair<int, int>> near_gaps(const NearLists& near, int endpoints) {
  std::vector<std::pair<int, int>> gaps;
  for (int e = 0; e < endpoints; ++e) {
    int taken = 0;
    for (int f : near[e]) {
      if (taken++ == kGreedyCandidates) break;
      if (f > e || !listed(near, f, e)) gaps.emplace_back(e, f);
    }
  }
  return gaps;
}

class Chains {
 public:
  explicit Chains(int strokes)
      : link_(2 * static_cast<std::size_t>(strokes), -1), parent_(strokes) {
    for (int s = 0; s < strokes; ++s) parent_[s] = s;
  }
  // Takes the gaps in order wherever both ends are still free and no loop closes; returns
  // how many were taken.
  int take(const std::vector<std::pair<int, int>>& gaps) {
    int taken = 0;
    for (const auto& [a, b] : gaps) {
      if (link_[a] >= 0 || link_[b] >= 0) continue;
      const int ra = root(a / 2), rb = root(b / 2);
      if (ra == rb) continue;
      link_[a] = b;
      link_[b] = a;
      parent_[ra] = rb;
      ++taken;
    }
    return taken;
  }
  int root(int s) {
    while (parent_[s] != s) s = parent_[s] = parent_[parent_[s]];
    return s;
  }
  std::vector<int> free_ends() const {
    std::vector<int> out;
    for (std::size_t e = 0; e < link_.size(); ++e) {
      if (link_[e] < 0) out.push_back(static_cast<int>(e));
    }
    return out;
  }
  const std::vector<int>& links() const { return link_; }

 private:
  std::vector<int> link_;    // per endpoint: the endpoint across its gap, or -1 (a chain end)
  std::vector<int> parent_;  // union-find over strokes: one root per chain
};

// The later rounds' gaps: between the chain ends left, each end's nearest ends of other chains.
std::vector<std::pair<int, int>> chain_end_gaps(const std::vector<Vec2>& ends, Chains& chains,
                                                const std::vector<int>& free_ends) {
  const PointGrid grid(ends, free_ends);
  std::vector<std::pair<int, int>> gaps;
  int found[kGreedyCandidates];
  for (int e : free_ends) {
    const int own = chains.root(e / 2);
    const int k = grid.k_nearest(
        ends[e], kGreedyCandidates, [&](int id) { return chains.root(id / 2) == own; }, found);
    for (int i = 0; i < k; ++i) {
      gaps.emplace_back(std::min(e, found[i]), std::max(e, found[i]));  // twice is harmless
    }
  }
  return gaps;
}

// link[e]: the endpoint e is joined to by a pen-up gap, or -1 where a chain ends. Greedy
// matching as for the travelling salesman: shortest gaps first, rounds over the chain ends
// left until one chain remains (or no gap joins two chains, or kMaxRounds).
std::vector<int> greedy_links(const std::vector<Vec2>& ends, const NearLists& near) {
  Chains chains(static_cast<int>(ends.size() / 2));
  chains.take(sorted(ends, near_gaps(near, static_cast<int>(ends.size()))));
  std::vector<int> free = chains.free_ends();
  for (int round = 0; round < kMaxRounds && free.size() > 2; ++round) {
    if (chains.take(sorted(ends, chain_end_gaps(ends, chains, free))) == 0) break;
    free = chains.free_ends();
  }
  return chains.links();
}

}  // namespace

std::vector<int> greedy_order(const std::vector<Vec2>& ends, const Vec2& start,
                              const NearLists& near, std::vector<char>& reversed) {
  const int n = static_cast<int>(ends.size() / 2);
  const std::vector<int> link = greedy_links(ends, near);
  std::vector<int> free_ends;  // chain ends: what the walk can enter by
  for (int e = 0; e < 2 * n; ++e) {
    if (link[e] < 0) free_ends.push_back(e);
  }
  std::vector<char> used(n, 0);
  std::vector<int> order;
  order.reserve(n);
  auto grid = std::make_unique<PointGrid>(ends, free_ends);
  std::size_t grid_size = free_ends.size(), alive = free_ends.size();
  Vec2 at = start;
  while (order.size() < static_cast<std::size_t>(n)) {
    // Rebuild over the remaining chain ends when three quarters are gone (as the plain
    // nearest-neighbour walk does): searches stay local, rebuilds cost n + n/4 + ...
    if (alive < grid_size / 4 && alive > 64) {
      std::vector<int> left;
      for (int e : free_ends) {
        if (!used[e / 2]) left.push_back(e);
      }
      grid = std::make_unique<PointGrid>(ends, left);
      grid_size = alive;
    }
    int e = grid->nearest(at, [&](int id) { return !used[id / 2]; });
    // Walk the chain: enter a stroke by e, leave by e ^ 1, cross the gap to link[e ^ 1].
    for (;;) {
      const int s = e / 2;
      used[s] = 1;
      reversed[s] = static_cast<char>(e % 2);
      order.push_back(s);
      if (link[e] < 0) {  // the chain's first stroke: entered by a chain end
        grid->forget(e);
        --alive;
      }
      if (link[e ^ 1] < 0) {  // its last: left by the other chain end
        grid->forget(e ^ 1);
        --alive;
        at = ends[e ^ 1];
        break;
      }
      e = link[e ^ 1];
    }
  }
  return order;
}

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

}  // namespace strand::post
