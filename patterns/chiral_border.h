// The specimen border of a chiral layer: frame edges pairing the odd-degree boundary nodes
// along the border polygon, and the grip tabs as detours of a bottom and a top frame edge.
#pragma once

#include <vector>

#include "patterns/chiral_lattice.h"
#include "slicer/toolpath.h"

namespace strand::patterns {

// A polyline edge: pts[i] -> pts[i + 1] drawn as feats[i].
struct EdgePath {
  std::vector<slicer::Vec2> pts;
  std::vector<slicer::Feature> feats;
  void add(const slicer::Vec2& p, slicer::Feature f) { pts.push_back(p), feats.push_back(f); }
};

// A frame edge between two boundary nodes, leaving each at an angle on its attach circle.
struct FrameEdge {
  int from = 0, to = 0;
  double angle_from_rad = 0.0, angle_to_rad = 0.0;
  EdgePath path;
};

struct ChiralFrame {
  std::vector<FrameEdge> edges;
  int grip_edge = -1;                        // the edge holding the bottom grip, -1 = none
  slicer::Vec2 mark = slicer::Vec2::Zero();  // start of the bottom grip's return line
};

// Frame edges for a lattice whose node ends (ligaments only) leave at `end_angles`; grips of
// `grip_mm` (0 = none) at line pitch about `nozzle_mm`. Never crosses a ligament or a pass.
ChiralFrame chiral_frame(const ChiralLattice& l, const NodeRings& rings,
                         const std::vector<std::vector<double>>& end_angles, double nozzle_mm,
                         double grip_mm);

}  // namespace strand::patterns
