// One `strand slice` job without printing or writing: mesh in, checked and placed; layers
// sliced and filled with the pattern; planned and emitted through post::produce.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "postprocess/plan/produce.h"
#include "slicer/mesh_check.h"
#include "slicer/tolerances.h"

namespace strand::cli {

// Work is bounded before any slicing: layers, and pattern segments clipped over all layers
// (about 10 s of clipping at most).
inline constexpr int kMaxSliceLayers = 20000;
inline constexpr double kMaxSliceSegments = 1e8;

struct SliceSettings {
  std::string part;                  // mesh file to fill (or empty with `onto`)
  std::string onto;                  // substrate mesh to lay the pattern on (or empty)
  std::string pattern = "scaffold";  // generator name
  nlohmann::json pattern_values = nlohmann::json::object();  // its flags as given (JSON form)
  int perimeters = 0;
  std::string mesh_units = "mm";
  std::string place = "center";
  std::string rotate = "0,0,0";  // X,Y,Z degrees
  bool repair = false;
  std::string machine = "deltawasp-2040-clay";
  std::string output = "slice.gcode";  // recorded in the report
  double arc_tolerance_mm = slicer::kDefaultArcToleranceMm;
};

struct SliceResult {
  post::Produced produced;
  slicer::Toolpath toolpath;
  slicer::PreparedMesh part;  // the mesh as sliced (placed), with its repairs; with `onto`,
                              // the placed substrate
};

// Throws InputError for any bad setting, file or mesh, and when the part does not fit.
// With `onto`, the pattern is the generator's own specimen (its extent flags apply) draped
// over the substrate mesh for a 3-axis machine (postprocess/plan/drape.h).
SliceResult produce_slice(const SliceSettings& settings);

// "1,2,3" -> (1, 2, 3) degrees; throws InputError naming slice.rotate.
slicer::Vec3 rotation_from_text(const std::string& text);

}  // namespace strand::cli
