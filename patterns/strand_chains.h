// Strands chained end to end through the joins taken at their ends: the walk that both the
// perimeter splices (patterns/perimeter_splice.h) and the neck links (patterns/neck_links.h)
// finish with.
#pragma once

#include <array>
#include <cstddef>
#include <utility>
#include <vector>

#include "slicer/toolpath.h"

namespace strand::patterns {

// Per strand, the join taken at its start [0] and at its end [1]; -1 where that end is free.
using EndJoins = std::vector<std::array<int, 2>>;

// Each chain, from a strand with a free end (in strand order): the strand, reversed when
// entered at its end; then `bridge(chain, j, s, leaves_at_start)` appends join j's way from
// where strand s leaves up to the next strand's first point and returns {next strand, entered
// at its start}; and so on to a free end. The joins must not close a chain on itself.
template <class Bridge>
std::vector<slicer::Stroke> chain_strands(const std::vector<slicer::Stroke>& strands,
                                          const EndJoins& join_at, const Bridge& bridge) {
  std::vector<slicer::Stroke> out;
  std::vector<bool> done(strands.size(), false);
  for (std::size_t first = 0; first < strands.size(); ++first) {
    if (done[first] || (join_at[first][0] >= 0 && join_at[first][1] >= 0)) continue;
    slicer::Stroke chain;
    std::size_t s = first;
    bool forward = join_at[first][0] < 0;  // enter at the free end
    for (;;) {
      done[s] = true;
      const slicer::Stroke piece = forward ? strands[s] : slicer::reversed(strands[s]);
      if (s == first) {
        chain = piece;
      } else {
        chain.segments.insert(chain.segments.end(), piece.segments.begin(), piece.segments.end());
      }
      const int j = join_at[s][forward ? 1 : 0];
      if (j < 0) break;
      const std::pair<std::size_t, bool> next =
          bridge(chain, static_cast<std::size_t>(j), s, !forward);
      s = next.first;
      forward = next.second;
    }
    out.push_back(std::move(chain));
  }
  return out;
}

}  // namespace strand::patterns
