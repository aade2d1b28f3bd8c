// Fewer strands from a region's joins by local search: a strand end whose ring neighbour
// is joined elsewhere takes that join over (a Posa rotation: the count stays, the end moves
// to the neighbour's old partner), a few steps deep, until two ends of different strands
// become ring neighbours and merge, or an end reaches the ring of a perimeter loop no other
// end can splice. Joins stay between ring neighbours, one per end, so nothing crosses.
#pragma once

#include <vector>

namespace strand::patterns {

// Piece p's ends are vertices 2p (start) and 2p + 1 (end).
struct JoinGraph {
  std::vector<int> next, prev;  // ring neighbours of each vertex (-1 = none)
  std::vector<int> loop_of;     // perimeter loop the vertex would splice (-1 = none)
  int loops = 0;                // innermost perimeter loops of the layer
};

// `mate[v]`: the ring neighbour v is joined to (-1: v ends a strand); mates are mutual and
// the pieces with their joins make open paths. Improved in place: fewer strands plus loops
// beside no strand end (each end splices at most one loop). Deterministic: ends tried in
// index order, rotations at most `depth` deep, and about `work_cap` path steps walked in all.
void improve_joins(const JoinGraph& g, std::vector<int>& mate, int depth = 5,
                   long long work_cap = 3'000'000);

// Strands and loops no strand end lies beside, for `mate` (the score improve_joins lowers).
int join_score(const JoinGraph& g, const std::vector<int>& mate);

}  // namespace strand::patterns
