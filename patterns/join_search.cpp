// Rotations and merges with undo; the score kept up to date as ends come and go.
#include "patterns/join_search.h"

namespace strand::patterns {

namespace {

class Search {
 public:
  Search(const JoinGraph& g, std::vector<int>& mate, long long cap)
      : g_(g), mate_(mate), on_loop_(static_cast<std::size_t>(g.loops), 0), cap_(cap) {
    for (int v = 0; v < static_cast<int>(mate_.size()); ++v) {
      if (mate_[v] < 0) add_end(v, +1);
    }
    strands_ = ends_ / 2;
  }

  int score() const { return strands_ + g_.loops - covered_; }

  void run(int depth) {
    for (bool improved = true; improved && work_ < cap_;) {
      improved = false;
      for (int x = 0; x < static_cast<int>(mate_.size()) && work_ < cap_; ++x) {
        if (mate_[x] >= 0) continue;
        base_ = score();
        improved = descend(x, depth) || improved;
      }
      if (!improved && g_.loops > 0) improved = split_once(depth);
    }
  }

 private:
  // Rotations never move an end to another ring (a join stays on its ring), so a loop beside
  // no end stays so: a join beside it is dropped (one strand more, the loop now spliceable)
  // when the strands it leaves can then merge elsewhere (one fewer again).
  bool split_once(int depth) {
    for (int u = 0; u < static_cast<int>(mate_.size()) && work_ < cap_; ++u) {
      const int u2 = mate_[u];
      const int l = g_.loop_of[static_cast<std::size_t>(u)];
      if (u2 < u || l < 0 || on_loop_[static_cast<std::size_t>(l)] > 0) continue;
      base_ = score();
      unmerge(u, u2);
      for (const int x : {u, u2, far_end(u), far_end(u2)}) {
        if (mate_[x] < 0 && descend(x, depth)) return true;
      }
      merge(u, u2);
    }
    return false;
  }

  // Tries merges and rotations from end x, `depth` rotations deep; keeps the first state
  // that scores below base_ and returns true, else leaves everything as it was.
  bool descend(int x, int depth) {
    for (const int y : {g_.next[x], g_.prev[x]}) {
      if (y < 0 || y == x || work_ >= cap_) continue;
      if (mate_[y] < 0) {
        if (far_end(x) == y) continue;  // the same strand: a join would close it
        merge(x, y);
        if (score() < base_) return true;
        unmerge(x, y);
        continue;
      }
      const int w2 = mate_[y];
      if (!rotation_keeps_path(x, y, w2)) continue;
      rotate(x, y, w2);
      if (score() < base_ || (depth > 1 && descend(w2, depth - 1))) return true;
      unrotate(x, y, w2);
    }
    return false;
  }

  // Walking from end x, the path meets w2 before w (or not at all): joining x to w after
  // dropping w-w2 leaves a path, not a closed loop.
  bool rotation_keeps_path(int x, int w, int w2) {
    for (int cur = x;; cur = mate_[cur ^ 1]) {
      ++work_;
      if (cur == w || (cur ^ 1) == w) return false;
      if (cur == w2 || (cur ^ 1) == w2) return true;
      if (mate_[cur ^ 1] < 0) return true;  // w is on another strand
    }
  }

  int far_end(int x) {
    int cur = x;
    for (; mate_[cur ^ 1] >= 0; cur = mate_[cur ^ 1]) ++work_;
    return cur ^ 1;
  }

  void add_end(int v, int sign) {
    ends_ += sign;
    const int l = g_.loop_of[static_cast<std::size_t>(v)];
    if (l < 0) return;
    int& n = on_loop_[static_cast<std::size_t>(l)];
    if (sign > 0 && n++ == 0) ++covered_;
    if (sign < 0 && --n == 0) --covered_;
  }

  void merge(int x, int y) {
    mate_[x] = y, mate_[y] = x;
    add_end(x, -1), add_end(y, -1);
    --strands_;
  }
  void unmerge(int x, int y) {
    mate_[x] = mate_[y] = -1;
    add_end(x, +1), add_end(y, +1);
    ++strands_;
  }
  // End x takes over w's join; w's old partner w2 becomes the end.
  void rotate(int x, int w, int w2) {
    mate_[w2] = -1;
    mate_[w] = x, mate_[x] = w;
    add_end(x, -1), add_end(w2, +1);
  }
  void unrotate(int x, int w, int w2) {
    mate_[x] = -1;
    mate_[w] = w2, mate_[w2] = w;
    add_end(w2, -1), add_end(x, +1);
  }

  const JoinGraph& g_;
  std::vector<int>& mate_;
  std::vector<int> on_loop_;  // strand ends beside each loop
  int ends_ = 0, strands_ = 0, covered_ = 0, base_ = 0;
  long long work_ = 0, cap_ = 0;
};

}  // namespace

void improve_joins(const JoinGraph& g, std::vector<int>& mate, int depth, long long work_cap) {
  Search(g, mate, work_cap).run(depth);
}

int join_score(const JoinGraph& g, const std::vector<int>& mate) {
  std::vector<int> copy = mate;
  return Search(g, copy, 0).score();
}

}  // namespace strand::patterns
