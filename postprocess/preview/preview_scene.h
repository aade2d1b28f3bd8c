// Room postprocess/preview (library strand_preview; links inspect, plan): pictures of a
// MotionProgram for people. It owns the scene (this file: polylines by layer and feature,
// colours), the cairo PNG/SVG views with optional check marks (preview_image.h), the
// self-contained HTML viewer and the glTF tubes. It never changes a program.
//
// What previews draw: a MotionProgram cut into polylines (deposit or travel, one layer and
// feature each, arcs flattened), with bounds and the colour scheme shared by every format.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "slicer/motion.h"
#include "slicer/surface.h"

namespace strand::post {

struct PreviewPath {
  int layer = -1;
  slicer::Feature feature = slicer::Feature::Infill;
  bool travel = false;
  std::vector<slicer::Vec3> points_mm;  // at least two
  int tool = 0;                         // pen or extruder, 0-based (pen k of a plot is tool k-1)

  bool operator==(const PreviewPath&) const = default;
};

struct PreviewScene {
  std::vector<PreviewPath> paths;
  std::vector<double> layer_z_mm;  // one per layer: its z, or on a substrate its offset
  // Bounds of the part: deposits on layers (not a purge line drawn before the first layer,
  // nor travels); all deposits when none is on a layer, all paths when there is no deposit.
  slicer::Vec3 min_mm = slicer::Vec3::Zero();
  slicer::Vec3 max_mm = slicer::Vec3::Zero();
  double bead_width_mm = 0.0;  // widest deposit (0 when the file gives no ;WIDTH:)
  // The substrate the paths lie on (a cylinder, a mesh patch) in the paths' frame, drawn
  // translucent under them; empty for planar files.
  slicer::TriangleMesh substrate;
  // False when the paths lie inside it (a part that `strand slice` filled): the mesh is then
  // a backdrop every path is drawn over, not a solid that hides what lies behind it.
  bool substrate_hides_paths = true;
  // What layer_z_mm holds, for labels: "z" (planar heights) or "offset" (the nozzle's
  // distance from a substrate).
  std::string layer_value = "z";
  // Pens' colours from the file ("#rrggbb" for pen 1, 2, ...; empty where not given).
  std::vector<std::string> pen_colours;
  // Deposits (not pens) come from more than one printhead (issue 33): coloured by tool.
  bool by_tool = false;

  bool operator==(const PreviewScene&) const = default;
};

// Arcs become chords within `arc_tolerance_mm`; `pen_colours` as ParsedGcode::pen_colours.
PreviewScene preview_scene(const slicer::MotionProgram& program, double arc_tolerance_mm,
                           std::vector<std::string> pen_colours = {});

// A scene from paths already in 3D, for programs that are not planar G-code (pose CSVs and
// rotary G-code mapped onto their substrate, toolpaths mapped through a Surface):
// `paths` with their layer (0-based, -1 before the first), feature and travel flag;
// `layer_offsets_mm` one per layer, the nozzle's offset from the substrate; `substrate` the
// substrate's triangles in the paths' frame (Surface::preview_mesh); `bead_width_mm` the
// bead drawn. Bounds as preview_scene computes them; layer_value "offset".
// Throws std::invalid_argument for a path with fewer than two points or a non-finite point.
PreviewScene scene_from_paths(std::vector<PreviewPath> paths, std::vector<double> layer_offsets_mm,
                              slicer::TriangleMesh substrate, double bead_width_mm);

// True when the scene needs a 3D view: it has a substrate, or a deposit leaves its layer's
// plane (z of the layer) by more than 0.001 mm.
bool is_3d(const PreviewScene& scene);

struct Rgb {
  double r = 0, g = 0, b = 0;  // 0..1
};
// Fixed colours per feature, close to PrusaSlicer's role colours where one exists.
Rgb feature_colour(slicer::Feature f);
// Blue (first layer) to red (last).
Rgb layer_colour(int layer, int layer_count);
std::string hex_colour(const Rgb& c);  // "#rrggbb"
// "#rrggbb" -> colour; nullopt for anything else.
std::optional<Rgb> parse_hex_colour(const std::string& text);

// What a deposit is drawn in when coloured by feature, and its legend entry: the feature
// ("wall", feature_colour), or for pen drawings each pen on its own ("pen 2", the pen's
// colour from the file, else a distinct colour per pen; pen 1 dark grey), or in a scene
// `by_tool` each printhead ("tool 1", its own colour).
struct PreviewKey {
  std::string name;
  Rgb colour;
  bool operator==(const PreviewKey& k) const { return name == k.name; }
};
PreviewKey deposit_key(const PreviewScene& scene, const PreviewPath& path);
// The keys of the deposits `keep` accepts (all when empty), features in enum order, pens by
// number: the legend's entries.
std::vector<PreviewKey> deposit_keys(const PreviewScene& scene,
                                     const std::function<bool(const PreviewPath&)>& keep = {});

}  // namespace strand::post
