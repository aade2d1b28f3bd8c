// A slice by objects (issue 33): several meshes in one frame (`--part FILE:TOOL`, or a 3MF's
// build items with `--tools objects=...`), each sliced and filled on its own and printed by
// its own printhead. Objects may not overlap in any layer (two inks would land on each other),
// so strands of different tools never cross; each layer prints one tool's strands after the
// other's, in an order that changes tool as few times as it can (or as given).
#pragma once

#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "jobs/slice_job.h"
#include "machines/profile.h"
#include "patterns/region_fill.h"
#include "slicer/mesh.h"
#include "slicer/mesh_check.h"
#include "slicer/mesh_io.h"
#include "slicer/region.h"

namespace strand::jobs {

// Objects one slice takes at most (each is sliced and checked against the others per layer).
inline constexpr std::size_t kMaxSliceObjects = 64;

// "a.stl:1" -> {"a.stl", 1} (the last colon splits); InputError naming --part and the form.
SlicePart part_from_text(const std::string& text);

// Whether `tools` (--tools text or a job's "tools") gives tools by object: "objects",
// "objects=1,0" or {"by_object": [1, 0]}.
bool tools_by_object(const nlohmann::json& tools);

// Whether the settings slice by objects (`parts` given, or tools by object).
bool slices_objects(const SliceSettings& s);

// Throws InputError naming slice.tool-order unless "fewest-changes" or "given".
void check_tool_order(const std::string& order);

struct SliceObject {
  std::string name;   // "a.stl", or "a.3mf object 1" (build order from 0)
  std::string given;  // what gave its tool, for messages: "--part = a.stl:1", "slice.tools = objects=1,0"
  slicer::Mesh mesh;  // as read; placed by place_objects
  int tool = 0;
};

// The objects of a slice by objects, read (the --part files, each file as one object; or the
// part's build items with the tools of `tools`: "objects" gives item k tool k). InputError for
// more than kMaxSliceObjects objects, a tool list whose length is not the object count, more
// triangles in all than one mesh may have, and a layer cycle with --part.
std::vector<SliceObject> read_slice_objects(const SliceSettings& s);

// Throws InputError naming what gave it when an object's tool is not on the machine.
void check_object_tools(const std::vector<SliceObject>& objects, const machines::MachineProfile& m);

// `placed` (the objects' meshes merged and placed as one part) cut back into the objects,
// each checked and repaired as asked, then all rested on the bed together again: the objects'
// meshes are replaced and the whole returned (changes and defects named by object); `rested`
// (may be null) is set to that last shift.
slicer::PreparedMesh prepare_objects(const slicer::Mesh& placed, std::vector<SliceObject>& objects,
                                     const slicer::PrepareOptions& options, slicer::Placement place,
                                     Eigen::Affine3d* rested = nullptr);

// Throws InputError naming the two objects and the layer where their regions share more than
// kObjectOverlapMm2 (`layers[i][k]`: object i's region in layer k).
inline constexpr double kObjectOverlapMm2 = 1e-3;
void check_objects_apart(const std::vector<SliceObject>& objects,
                         const std::vector<std::vector<slicer::Region>>& layers, double layer_height_mm);

// What a layer fill lacks, added to one object's fill before its strokes get the tool
// (a centre bead on a top no pattern reaches: jobs/slice_material_bead.h).
using FillCompletion = std::function<void(const slicer::Region&, patterns::LayerFill&)>;

// The objects' layers, each filled by its own source (part_fill_layers of objects[i]'s fill)
// and its strokes given tools[i]; per layer the tools in `order` ("fewest-changes": the tool
// of the layer below's last strand first, the rest ascending; "given": the objects' order),
// each tool's strands in nearest-first order. region(k) and the derived sizes are those of
// all objects together, as part_fill_layers gives them for one part.
std::unique_ptr<patterns::PartFillSource> objects_fill_layers(std::vector<patterns::PartFill> objects,
                                                              std::vector<int> tools,
                                                              const patterns::RegionPattern& p,
                                                              const std::string& order,
                                                              FillCompletion complete);

// Layer k of every object, side by side (the regions do not overlap).
std::vector<slicer::Region> joined_layers(const std::vector<std::vector<slicer::Region>>& layers);

}  // namespace strand::jobs
