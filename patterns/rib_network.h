// A plane network of straight ribs and its traversal by as few non-crossing strands as
// possible: where ribs meet, each strand turns into a neighbouring rib instead of going
// straight through, so passes at a node touch but never cross.
#pragma once

#include <vector>

#include "slicer/toolpath.h"

namespace strand::patterns {

// Vertices and straight edges of a plane graph whose edges meet only at vertices. A
// network wrapped round a cylinder is periodic in x: an edge across the seam reaches b's
// copy `wrap` periods away (b drawn at its position + wrap * period_mm along x).
struct RibNetwork {
  struct Edge {
    int a = 0;
    int b = 0;
    slicer::Feature feature = slicer::Feature::Ligament;
    int wrap = 0;
  };
  std::vector<slicer::Vec2> vertices_mm;
  std::vector<Edge> edges;
  double period_mm = 0.0;  // 0: flat

  int add_vertex(const slicer::Vec2& p_mm);
  void add_edge(int a, int b, slicer::Feature feature, int wrap = 0);
};

// Closed strands covering every edge once. Every vertex must have even degree (throws
// std::logic_error otherwise). At each vertex the passes pair cyclically neighbouring
// edges, so no two passes cross there; circuits meeting at a degree-4 vertex are merged by
// switching its pairing, giving one strand per connected component.
// With node_gap_mm > 0, a pass through a vertex where four or more edges meet cuts the
// corner (a Node segment) so that it stays node_gap_mm / 2 from the vertex: two passes on
// opposite sides then lie node_gap_mm apart and, for node_gap_mm = d, touch side by side
// instead of piling up on the vertex. Each strand starts at its lowest-numbered vertex, or
// at the next vertex of degree 2 along it if that one is a node; strands come in the order
// of their start vertex. On a periodic network a strand runs on past the seam (its points
// continue beyond the period), so it stays continuous.
std::vector<slicer::Stroke> non_crossing_circuits(const RibNetwork& net, double node_gap_mm = 0.0);

}  // namespace strand::patterns
