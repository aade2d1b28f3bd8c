// The specimen border of a chiral layer: frame edges pairing the odd-degree boundary nodes
// along the border polygon, and the grip tabs as detours of a bottom and a top frame edge;
// for a ring lattice (round a cylinder) only at its two ends, the grips as bands all round.
#pragma once

#include <vector>

#include "patterns/chiral_lattice.h"
#include "slicer/toolpath.h"

namespace strand::patterns {

// A polyline edge: pts[i] -> pts[i + 1] drawn as feats[i], in the frame of its first node.
// On a ring lattice the path may end at its last node's copy `wrap` periods away along x.
struct EdgePath {
  std::vector<slicer::Vec2> pts;
  std::vector<slicer::Feature> feats;
  int wrap = 0;
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
  slicer::Vec2 mark = slicer::Vec2::Zero();  // where the strand starts, in that edge's frame
};

// Frame edges for a lattice whose node ends (ligaments only) leave at `end_angles`; grips of
// `grip_mm` (0 = none) at line pitch about `nozzle_mm`. Never crosses a ligament or a pass.
ChiralFrame chiral_frame(const ChiralLattice& l, const NodeRings& rings,
                         const std::vector<std::vector<double>>& end_angles, double nozzle_mm,
                         double grip_mm);

// The border of a ring lattice (lattice.period_mm > 0): at each end row, frame edges pair
// the odd-degree nodes in order of x along a frame line one layer height outside the attach
// circles (no frame along the seam); with grip_mm > 0, a grip band all round each end as a
// detour of the frame edge nearest x = 0, or of a loop edge at the node nearest x = 0 when
// the row has no odd node. The band's serpentine runs once round the cylinder, so that edge
// ends one period away (wrap -1). Precondition: an even number of odd nodes per end row.
ChiralFrame chiral_ring_frame(const ChiralLattice& l, const NodeRings& rings,
                              const std::vector<std::vector<double>>& end_angles,
                              double nozzle_mm, double grip_mm);

// How a frame edge leaves node `c` for frame point `p`: its end angle on the attach circle
// and the connector points out to (not including) p. A straight radial connector unless a
// ligament's tangent point lies just clockwise of it; then it leaves a little clockwise of
// that tangent point, steps out to the frame radius and runs to p on the far side.
struct FrameAttach {
  double angle_rad = 0;
  std::vector<slicer::Vec2> pts;
};
FrameAttach frame_attach(const slicer::Vec2& c, const std::vector<double>& ligament_angles,
                         const NodeRings& rings, const slicer::Vec2& p);

}  // namespace strand::patterns
