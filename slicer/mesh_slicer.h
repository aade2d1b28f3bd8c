// Planar slices of a triangle soup: every triangle cut by the plane gives one oriented
// segment; segments chain into loops through their shared end points (gaps up to
// kMaxContourGapMm closed), and the loops' nonzero union is the layer's region. Overlapping
// shells, self-intersections, non-manifold edges and vertices, inside-out shells and small
// holes then still give the solid's section.
#pragma once

#include <cstddef>
#include <vector>

#include "slicer/mesh.h"
#include "slicer/region.h"

namespace strand::slicer {

// Loose contour ends this close are joined (a crack or a small hole in the surface).
inline constexpr double kMaxContourGapMm = 2.0;

// What the chaining had to mend, summed over the slices it made.
struct ContourStats {
  std::size_t gaps_closed = 0;        // ends joined across a gap (0 < gap <= kMaxContourGapMm)
  double widest_gap_mm = 0.0;         // the widest of those
  std::size_t wide_gaps_closed = 0;   // open loops closed across more than kMaxContourGapMm
  std::size_t reversed_segments = 0;  // segments of flipped triangles followed backwards
  std::size_t dropped_pieces = 0;     // open pieces of fewer than 3 points, left out
  ContourStats& operator+=(const ContourStats& o);
};

class MeshSlicer {
 public:
  explicit MeshSlicer(const Mesh& m);
  const Mesh& mesh() const { return mesh_; }
  const std::vector<double>& vertex_z() const { return vertex_z_; }

 private:
  Mesh mesh_;
  std::vector<double> vertex_z_;  // sorted, to move planes off vertices
};

// Closed loops (first point not repeated at the end) where the plane z = z_mm cuts the mesh,
// oriented with the solid on the left (counter-clockwise around an outward-facing shell's
// section). A plane that meets a vertex exactly is moved up by kSliceNudgeMm.
std::vector<Ring> slice_at(const MeshSlicer& slicer, double z_mm, ContourStats* stats = nullptr);

// The regions of `layers` layers of height `layer_height_mm` over a part resting on z = 0:
// layer k is the nonzero union of the loops at mid-layer, z = (k + 0.5) * layer height.
std::vector<Region> slice_layers(const Mesh& m, double layer_height_mm, int layers,
                                 ContourStats* stats = nullptr);

// slice_layers one layer at a time: the triangles each plane meets are found once, in one
// sweep up the part; then cut(k) gives layer k's region, for any k in any order, from several
// threads at once (jobs/ cuts the layers in parallel). Same regions as slice_layers.
class LayerCuts {
 public:
  LayerCuts(const Mesh& m, double layer_height_mm, int layers);
  int layers() const { return static_cast<int>(active_.size()); }
  // Layer k's region; what the chaining mended is added to `stats` (one per thread).
  Region cut(int k, ContourStats& stats) const;

 private:
  MeshSlicer slicer_;
  std::vector<double> z_mm_;              // each layer's plane, moved off vertices
  std::vector<std::vector<int>> active_;  // per layer: the triangles it meets, in mesh order
};

}  // namespace strand::slicer
