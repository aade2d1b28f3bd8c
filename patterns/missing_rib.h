// Missing-rib auxetic lattice (Smith, Grima & Evans 2000 type) in the part plane: a square
// network of four-rib nodes alternately rotated by +theta and -theta, so each pair of
// neighbouring nodes is joined by two ribs meeting at a re-entrant bend; pulling the
// lattice straightens the bends and rotates the nodes, which opens it in both directions.
// Each layer is one closed strand that turns at every node (no crossing): the two passes
// through a node each cut its corner, by default one nozzle apart, so they touch side by side.
#pragma once

#include <memory>
#include <nlohmann/json.hpp>

#include "slicer/layer_source.h"
#include "slicer/params.h"
#include "slicer/toolpath.h"

namespace strand::patterns {

struct MissingRibParams {
  double nozzle_mm = 0.84;          // filament diameter d
  double rib_mm = 6.0;              // length of every rib, node to bend
  double angle_deg = 20.0;          // rib angle theta: rotation of each node's ribs
  double node_gap_mm = 0.84;        // distance between the two passes turning at a node (d)
  int rows = 4;                     // cells along y
  int cols = 4;                     // cells along x
  int layers = 4;
  double layer_height_mm = 0.672;   // 0.8 d by default
  double speed_mm_per_min = 250.0;
};

// Sizes derived from the parameters, computed in one place.
// Nodes sit on a square grid of pitch p = 2 * rib * cos(theta), (rows + 1) x (cols + 1) of
// them. Boundary nodes keep their outward ribs, which end on a frame half a pitch outside
// the node grid; frame pieces join those rib ends in pairs, so every vertex has even degree.
struct MissingRibGeometry {
  double pitch_mm = 0.0;
  double frame_width_mm = 0.0;      // frame centre line, x extent: (cols + 1) * pitch
  double frame_depth_mm = 0.0;      // (rows + 1) * pitch
  double width_mm = 0.0;            // outer size: frame centre line + nozzle
  double depth_mm = 0.0;
  double height_mm = 0.0;           // layers * layer height
  // Narrowest centre-line clearance between filaments that are not joined: outward bend to
  // frame, rib (cos - sin) (bend to bend across a cell is twice that), and the span of a rib
  // left after its node's corner cut, (rib - node gap / sqrt 2) cos, mm.
  double min_clearance_mm = 0.0;
};

MissingRibGeometry missing_rib_geometry(const MissingRibParams& p);
// Layers centred on (0, 0); layer k at z = (k + 1) * layer height, one closed strand each.
std::unique_ptr<slicer::LayerSource> missing_rib_layers(const MissingRibParams& p);
slicer::Toolpath generate_missing_rib(const MissingRibParams& p);

// `--wrap full` round a circumference `period_mm` (x, periodic): an even number of nodes
// round it (the rotations alternate), the pitch adjusted to fit by adjusting the rib at the
// same angle (at least the smallest valid rib), cols ignored; frame pieces pair the outward
// ribs only at the two ends. One closed strand per layer, running on past the seam.
slicer::Toolpath generate_missing_rib_wrapped(const MissingRibParams& p, double period_mm);
// Shortest rib for which filaments that are not joined stay a nozzle apart, mm.
double missing_rib_min_rib_mm(const MissingRibParams& p);

// Parameter table (CLI flags and job keys) and the checked conversion from its values.
const slicer::ParamTable& missing_rib_table();
MissingRibParams missing_rib_params_from(const nlohmann::json& values);

}  // namespace strand::patterns
