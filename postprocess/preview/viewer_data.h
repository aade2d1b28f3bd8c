// The 3D toolpath viewer's data (issue 34): an index (layers with their z and stats, bounds,
// features, colour ranges, the substrate) and binary layer blocks of segments, built once per
// file and served in layer ranges (`strand serve`) or inlined (`strand preview -o x.html`), so
// a million-move file travels as typed arrays, not as JSON per move.
#pragma once

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "machines/profile.h"
#include "postprocess/preview/preview_scene.h"

namespace strand::post {

// One layer's block, n segments, little-endian, each array starting at a multiple of 4 bytes:
//   Float32 pos[6n]   x0 y0 z0 x1 y1 z1 per segment (mm; arcs as chords)
//   Float32 feed[n]   mm/min (0 when unknown: pose programs)
//   Float32 flow[n]   E per mm of the move (0 for travels and files without E)
//   Uint32  line[n]   the move's 1-based G-code line (0 when unknown)
//   Uint8   kind[n]   feature code (index into the index's "features"), +128 for a travel
//   Uint8   tool[n]   extruder or pen, 0-based
// then zero padding to a multiple of 4.
inline constexpr std::size_t kViewerSegmentBytes = 6 * 4 + 4 + 4 + 4 + 1 + 1;
inline constexpr std::uint8_t kViewerTravelBit = 128;
std::size_t viewer_block_bytes(std::size_t segments);

struct ViewerSegment {
  slicer::Vec3 from_mm = slicer::Vec3::Zero(), to_mm = slicer::Vec3::Zero();
  float feed_mm_per_min = 0, e_per_mm = 0;
  std::uint32_t line = 0;
  std::uint8_t kind = 0, tool = 0;
  bool operator==(const ViewerSegment&) const = default;
};

// Per-layer figures beside the view (the estimate's: strands, lengths, naive or, with a
// machine, trapezoidal time; E summed from the file's E words).
struct ViewerLayer {
  double z_mm = 0.0;
  std::size_t segments = 0, moves = 0;
  std::size_t offset = 0;  // of its block in ViewerData::blocks, bytes
  int strands = 0;
  double deposit_length_mm = 0.0, travel_length_mm = 0.0, time_s = 0.0, e = 0.0;
};

struct ViewerData {
  std::string source;               // the file's name, for titles
  std::vector<ViewerLayer> layers;  // at least one
  std::string blocks;               // the layers' blocks, in order
  slicer::Vec3 min_mm = slicer::Vec3::Zero(), max_mm = slicer::Vec3::Zero();
  double max_feed_mm_per_min = 0.0, max_e_per_mm = 0.0;  // of deposits, for colour scales
  double bead_width_mm = 0.0;
  bool trapezoid_time = false;   // time_s is the machine's trapezoidal estimate
  std::string layer_value = "z";  // "z" or "offset" (pose programs: distance from the substrate)
  slicer::TriangleMesh substrate;  // drawn translucent beneath; empty for planar files
  slicer::TriangleMesh part;       // a slice's part, drawn translucent on the bed; or empty
  std::string part_note;           // why a slice's part is not drawn, or empty
  bool pens = false;                     // some deposits are pen strokes
  std::vector<std::string> pen_colours;  // as ParsedGcode::pen_colours
  int max_tool = 0;                      // highest tool of a deposit
};

// A G-code file read layer by layer (memory: its segments, not its moves); `machine` (may be
// null) gives the trapezoidal time. Moves before the first layer go with the first layer.
// Throws InputError as the parser does, and for a file without moves.
ViewerData viewer_data_from_gcode(std::string_view text, const machines::MachineProfile* machine,
                                  double arc_tolerance_mm, const std::string& source);
// A scene already in 3D (pose programs and rotary files on their substrate): paths become
// segments; no feed, flow or time.
ViewerData viewer_data_from_scene(const PreviewScene& scene, const std::string& source);

// The index the viewer reads first: "layers" (z, segments, moves, offset, bytes, strands,
// deposit_length_mm, travel_length_mm, time_s, e), "bounds", "features", "feed_max",
// "flow_max", "bead_width_mm", "layer_value", "time", "segments", "source", "pens" (for pen
// drawings: each pen's legend name and colour, as deposit_key gives them), and "substrate"
// ({"v": [x, y, z, ...], "t": [i, j, k, ...]}) when there is one; "part" (the same, vertices
// to 0.1 um) and "part_note" for a slice's part.
nlohmann::json viewer_index(const ViewerData& data);
// The bytes of layers [from, to] (the caller checks the range).
std::string_view viewer_blocks(const ViewerData& data, std::size_t from, std::size_t to);
// Decodes one block back into segments (tests, and a check of a cached file's size).
std::vector<ViewerSegment> decode_viewer_block(std::string_view block, std::size_t segments);

}  // namespace strand::post
