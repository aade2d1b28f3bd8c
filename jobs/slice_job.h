// One `strand slice` job without printing or writing: mesh in, checked and placed; layers
// sliced and filled with the pattern; planned and emitted through post::produce.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "postprocess/plan/produce.h"
#include "slicer/mesh_check.h"
#include "slicer/progress_listener.h"
#include "slicer/tolerances.h"

namespace strand::jobs {

// Work is bounded before any slicing: layers, and pattern segments clipped over all layers
// (about 10 s of clipping at most).
inline constexpr int kMaxSliceLayers = 20000;
inline constexpr double kMaxSliceSegments = 1e8;
inline constexpr int kMaxSliceThreads = 256;

// One object of a multi-object slice as `--part FILE:TOOL` gives it (issue 33).
struct SlicePart {
  std::string path;
  int tool = 0;
  bool operator==(const SlicePart&) const = default;
};

struct SliceSettings {
  std::string part;                  // mesh file to fill (or empty with `onto` or `parts`)
  // --part FILE:TOOL (repeatable), instead of `part`: several meshes in one frame (each
  // file's own coordinates), placed together, each filled in its printhead's ink
  // (jobs/slice_objects.h).
  std::vector<SlicePart> parts;
  // The tools' order in each layer of a slice by objects: "fewest-changes" (the tool the
  // machine holds first, the others ascending) or "given" (the objects' order).
  std::string tool_order = "fewest-changes";
  std::string part_name;             // recorded as the part instead of `part` (the workbench
                                     // names its upload so), or empty
  std::string onto;                  // substrate mesh to lay the pattern on (or empty)
  std::string pattern = "scaffold";  // generator name
  nlohmann::json pattern_values = nlohmann::json::object();  // its flags as given (JSON form)
  int perimeters = 0;
  std::string mesh_units = "mm";
  std::string place = "center";
  std::string rotate = "0,0,0";  // X,Y,Z degrees
  bool repair = false;
  bool strict = false;       // refuse any mesh defect instead of slicing the soup
  bool viewer_e = false;     // also write OUTPUT.viewer-e.gcode with computed E (preview only)
  double scale = 1.0;        // uniform scale after the units (--scale)
  std::string scale_to_fit;  // "WxDxH" mm: the largest uniform scale that fits (or empty)
  std::string up = "z";      // the file's up axis: z, or y (turned to +z)
  // Called with the placed part's size before any slicing work (the CLI prints it).
  std::function<void(const slicer::Vec3& size_mm)> on_part_size;
  // Told each phase (reading, checking, slicing, filling layers, planning, G-code); not
  // owned, null: nobody.
  slicer::Progress* progress = nullptr;
  std::string machine = "deltawasp-2040-clay";
  std::string output = "slice.gcode";  // recorded in the report (the CLI: PART's name.gcode)
  double arc_tolerance_mm = slicer::kDefaultArcToleranceMm;
  // Threads that cut, fill and plan the layers, in [1, 256]; unset: every core. The bytes
  // written are the same for any number (jobs/slice_parallel.h).
  std::optional<int> threads;
  // --tools: printheads by feature (wall=1,infill=0: perimeters in another ink) or cycled per
  // layer (layers=0,1), as on every generator (postprocess/plan/tool_assignment.h); or by
  // object of a 3MF (objects, objects=1,0, {"by_object": [1, 0]}: jobs/slice_objects.h);
  // null: none.
  nlohmann::json tools;
};

struct SliceResult {
  post::Produced produced;
  slicer::Toolpath toolpath;        // generator, parameters, derived; a sliced part's layers are
                                   // not kept (written as they were filled), a draped one's are
  slicer::PreparedMesh part;       // the mesh as sliced (placed), with its repairs; with `onto`,
                                   // the placed substrate
  double scale = 1.0;              // the uniform scale applied (after units)
  std::vector<std::string> notes;  // defects handled and regions skipped, for the summary
};

// Largest scale at which `size_mm` fits in the box "WxDxH" (mm); throws InputError naming
// slice.scale-to-fit for a malformed box.
double scale_to_fit(const slicer::Vec3& size_mm, const std::string& box);

// Throws InputError for any bad setting, file or mesh, and when the part does not fit.
// With `onto`, the pattern is the generator's own specimen (its extent flags apply) draped
// over the substrate mesh for a 3-axis machine (postprocess/plan/drape.h).
SliceResult produce_slice(const SliceSettings& settings);
// What `strand slice` prints after the part's size (every front end shows the same): the
// job's summary, then the pattern, thin beads, layer, substrate, repair, scale and note lines.
std::string slice_summary_text(const SliceResult& r, const SliceSettings& s);

// Throws InputError naming slice.threads unless unset or in [1, kMaxSliceThreads].
void check_threads(const std::optional<int>& threads);
// "4" -> 4 for --threads; throws InputError naming slice.threads for anything but a whole
// number in [1, kMaxSliceThreads].
int threads_from_text(const std::string& text);

// "1,2,3" -> (1, 2, 3) degrees; throws InputError naming slice.rotate.
slicer::Vec3 rotation_from_text(const std::string& text);

}  // namespace strand::jobs
