// One continuous, non-crossing strand per layer of a chiral lattice specimen: ligaments,
// a hairpin of concentric passes at every node visit, a border frame that makes every
// degree even, and solid zig-zag grip tabs at both ends, joined by a non-crossing Euler
// circuit.
#pragma once

#include <vector>

#include "patterns/chiral_lattice.h"
#include "slicer/toolpath.h"

namespace strand::patterns {

struct StrandSpec {
  double nozzle_mm = 0.5;
  double layer_height_mm = 0.4;
  double grip_mm = 0.0;  // grip tab length beyond the frame, 0 = no grips
};

// The closed strands of one layer (one when the circuit joins everything), starting and
// ending in the bottom grip when there is one.
std::vector<slicer::Stroke> chiral_layer(const ChiralLattice& lattice, const NodeRings& rings,
                                         const StrandSpec& spec);

// The segments of one node visit: arrive at `entry_rad` on the attach circle, pass
// through the sector of signed `sweep_rad`, leave at entry + sweep. Passes alternate
// direction from the outermost to the innermost, which ends at the exit; all but the
// outermost may turn `extend_rad` back beyond the entry (into an empty gap), else they
// turn a small margin inside the sector.
std::vector<slicer::Segment> node_hairpin(const slicer::Vec2& centre, const NodeRings& rings,
                                          double entry_rad, double sweep_rad,
                                          double extend_rad = 0.0);

}  // namespace strand::patterns
