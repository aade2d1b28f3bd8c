// Non-crossing Euler circuits on a plane graph: at every vertex the strand pairs edge ends
// that are neighbours in angular order, so no two visits of a vertex interleave and the
// strand never crosses itself there.
#pragma once

#include <vector>

namespace strand::patterns {

// A plane graph given by its edges and the angle at which each edge end leaves its vertex.
struct PlaneGraph {
  int vertex_count = 0;
  std::vector<int> edge_from, edge_to;               // vertex indices
  std::vector<double> angle_from_rad, angle_to_rad;  // direction of the end at that vertex
  int add_edge(int from, int to, double angle_from_rad, double angle_to_rad);
};

// One edge walked in a circuit; `forward` walks it from edge_from to edge_to.
struct CircuitStep {
  int edge = 0;
  bool forward = true;
  bool operator==(const CircuitStep&) const = default;
};

// Closed curves that together use every edge once; every vertex visit pairs two ends
// adjacent in angular order, never the two ends of a loop. One curve when the graph is
// connected with all degrees even (degree 4 is guaranteed; higher degrees are merged by
// flipping one vertex, or a vertex and a neighbour, while that merges curves, and checked by
// the caller). Deterministic: starts from edge 0 and vertices in index order.
std::vector<std::vector<CircuitStep>> noncrossing_circuits(const PlaneGraph& g);

}  // namespace strand::patterns
