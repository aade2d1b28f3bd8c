// Planar slices of a closed mesh with CGAL's Polygon_mesh_slicer over an AABB tree of the
// mesh's edges: built once, then asked for the contours at any height.
#pragma once

#include <memory>
#include <vector>

#include "slicer/mesh.h"
#include "slicer/region.h"

namespace strand::slicer {

class MeshSlicer {
 public:
  explicit MeshSlicer(const Mesh& m);
  ~MeshSlicer();
  MeshSlicer(const MeshSlicer&) = delete;
  MeshSlicer& operator=(const MeshSlicer&) = delete;

  struct Impl;
  const Impl& impl() const { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

// Closed contours (first point not repeated at the end) where the plane z = z_mm cuts the
// mesh, in no particular orientation; open pieces (from an open mesh) are dropped. A plane
// that meets a vertex exactly is moved up by kSliceNudgeMm so contours stay simple.
std::vector<Ring> slice_at(const MeshSlicer& slicer, double z_mm);

// The regions of `layers` layers of height `layer_height_mm` over a part resting on z = 0:
// layer k is the slice at mid-layer, z = (k + 0.5) * layer height.
std::vector<Region> slice_layers(const Mesh& m, double layer_height_mm, int layers);

}  // namespace strand::slicer
