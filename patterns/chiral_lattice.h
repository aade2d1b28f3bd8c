// Chiral lattice geometry shared by the tetrachiral and hexachiral generators: node
// positions, ligaments as internal tangents, concentric pass radii, the border polygon
// and the smallest cell for which ligaments clear the nodes and each other.
#pragma once

#include <utility>
#include <vector>

#include "slicer/geometry.h"

namespace strand::patterns {

// Nodes and ligaments of a lattice in the part frame (mm), plus the boundary cycle.
// A ring lattice (wrapped round a cylinder) is periodic in x: its nodes lie in one period
// [-period / 2, period / 2) and a ligament across the seam reaches a node's copy one period
// away, so its geometry is taken with the far node shifted by wraps[k] * period along x.
struct ChiralLattice {
  std::vector<slicer::Vec2> nodes;
  std::vector<std::pair<int, int>> ligaments;  // node indices
  std::vector<int> boundary;                   // outer nodes, counter-clockwise (flat only)
  double cell_mm = 0.0;                        // centre-to-centre distance of neighbours
  double period_mm = 0.0;                      // ring: the period along x; 0 = flat
  std::vector<int> wraps;                      // ring: per ligament; empty when flat
};

// The two node centres of ligament k as it is drawn: the second shifted by its wrap.
std::pair<slicer::Vec2, slicer::Vec2> ligament_nodes(const ChiralLattice& l, std::size_t k);

// Square grid of (cols + 1) x (rows + 1) nodes, pitch `cell_mm`, centred on (0, 0).
ChiralLattice tetrachiral_lattice(int cols, int rows, double cell_mm);
// Triangular lattice: rows + 1 rows of cols + 1 nodes, odd rows shifted by cell / 2,
// rows cell * sin 60 apart, centred on (0, 0).
ChiralLattice hexachiral_lattice(int cols, int rows, double cell_mm);
// Ring versions: rows + 1 rows of `around` nodes, period around * cell; rows centred on
// y = 0, x in [-period / 2, period / 2) with the seam between nodes.
ChiralLattice tetrachiral_ring(int around, int rows, double cell_mm);
ChiralLattice hexachiral_ring(int around, int rows, double cell_mm);

// Radii of the passes around a node. The thesis' core is the hole left inside the inner
// pass: innermost pass at core / 2 + d / 2, passes h apart, ligaments attached one h
// outside the outermost pass, the frame one h outside the attach circle.
struct NodeRings {
  std::vector<double> pass_mm;  // innermost first
  double middle_mm = 0.0;       // the thesis' r (middle pass; r = core/2 + h + d/2 for 3)
  double attach_mm = 0.0;       // ligaments are tangent to this circle
  double frame_mm = 0.0;        // border polygon offset from the boundary nodes
  double ring_width_mm = 0.0;   // edge to edge: (passes - 1) h + d
};
NodeRings node_rings(double core_mm, double nozzle_mm, double layer_height_mm, int passes);

// Internal tangent of two circles of `radius_mm` around a and b: the ligament from a to
// b. Leaving a it runs counter-clockwise around a (one handedness for the whole lattice).
// Returns the tangent points {on a, on b}.
std::pair<slicer::Vec2, slicer::Vec2> ligament_tangent(const slicer::Vec2& a, const slicer::Vec2& b,
                                                       double radius_mm);
// Ligament angle to the centre line, sin(alpha) = 2 radius / cell.
double ligament_angle_rad(double cell_mm, double radius_mm);

// Border polygon: the boundary cycle offset outward by `offset_mm` (mitred corners), one
// point per boundary node, in the same order.
std::vector<slicer::Vec2> border_polygon(const ChiralLattice& lattice, double offset_mm);

// Clearances of a lattice: the least distance from a ligament to a node it does not touch
// (minus the outer pass), and between two ligaments that share no node.
struct Clearance {
  double node_mm = 0.0;
  double ligament_mm = 0.0;
};
Clearance lattice_clearance(const ChiralLattice& lattice, const NodeRings& rings);
// Smallest cell (mm, rounded up to 0.01) for which ligaments are at least one nozzle long
// and both clearances are at least the nozzle, on a small patch built by `make(cell)`.
double min_cell_mm(ChiralLattice (*make)(int, int, double), const NodeRings& rings,
                   double nozzle_mm);

}  // namespace strand::patterns
