// The slice pipeline: read, check, place, slice, fill, produce.
#include "jobs/slice_job.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>

#include <tbb/task_arena.h>

#include "jobs/job_runner.h"
#include "jobs/slice_layer_stats.h"
#include "jobs/slice_material_bead.h"
#include "jobs/slice_objects.h"
#include "jobs/slice_parallel.h"
#include "jobs/slice_placement.h"
#include "jobs/slice_thin_walls.h"
#include "machines/profile.h"
#include "patterns/region_fill.h"
#include "patterns/registry.h"
#include "patterns/thin_feature.h"
#include "postprocess/plan/drape.h"
#include "slicer/input_error.h"
#include "slicer/mesh_io.h"
#include "slicer/mesh_slicer.h"
#include "slicer/mesh_surface.h"
#include "slicer/params.h"
#include "slicer/unit_values.h"

namespace strand::jobs {

namespace {

std::string pattern_names() {
  std::string out;
  for (const auto& g : patterns::generators()) out += (out.empty() ? "" : ", ") + g.name;
  return out;
}

void check_settings(const SliceSettings& s) {
  if (s.perimeters < 0 || s.perimeters > 20) {
    throw InputError("slice.perimeters = " + std::to_string(s.perimeters) + ": must be in [0, 20]");
  }
  if (!(s.arc_tolerance_mm > 0.0 && s.arc_tolerance_mm <= 1.0)) {
    throw InputError("arc-tolerance = " + slicer::short_number(s.arc_tolerance_mm) +
                     ": must be in (0, 1] (mm)");
  }
  check_threads(s.threads);
  check_tool_order(s.tool_order);
}

slicer::MeshPlacement placement_of(const SliceSettings& s) {
  slicer::MeshPlacement placement;
  placement.mm_per_unit = slicer::mm_per_mesh_unit("slice.mesh-units", s.mesh_units);
  placement.place = slicer::placement_from("slice.place", s.place);
  placement.rotate_deg = rotation_from_text(s.rotate);
  return placement;
}

// "0.5" -> 0.5 for --scale; throws naming slice.scale outside (0, 1000].
void check_scale(double scale) {
  if (!(scale > 0.0 && scale <= 1000.0)) {
    throw InputError("slice.scale = " + slicer::short_number(scale) + ": must be in (0, 1000]");
  }
}

std::string size_text(const slicer::Vec3& size) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "%.3f x %.3f x %.3f mm", size.x(), size.y(), size.z());
  return buf;
}

std::string mm_text(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3f", v);
  return buf;
}

// The part (or, with `objects`, the objects read and placed together as one part), checked;
// `placed` is set to the map from the files' coordinates (as read) to the part frame.
slicer::PreparedMesh load_part(const SliceSettings& s, double& scale, std::vector<SliceObject>* objects,
                               Eigen::Affine3d& placed) {
  if (s.up != "z" && s.up != "y") throw InputError("slice.up = " + s.up + ": must be z or y");
  std::vector<std::string> paths = {s.part};
  if (!s.parts.empty()) paths.clear();
  for (const SlicePart& p : s.parts) paths.push_back(p.path);
  for (const std::string& path : paths) {
    const std::string ext = std::filesystem::path(path).extension().string();
    if (s.up == "y" && (ext == ".gltf" || ext == ".glb" || ext == ".GLTF" || ext == ".GLB")) {
      throw InputError("slice.up = y: glTF is +Y up by definition and is turned to +Z already");
    }
    if ((ext == ".3mf" || ext == ".3MF") && s.mesh_units != "mm") {
      throw InputError("slice.mesh-units = " + s.mesh_units +
                       ": a 3MF file states its own unit (use --scale to resize it)");
    }
  }
  check_scale(s.scale);
  if (!s.scale_to_fit.empty() && s.scale != 1.0) {
    throw InputError("slice.scale-to-fit = " + s.scale_to_fit +
                     ": give --scale or --scale-to-fit, not both");
  }
  const slicer::MeshPlacement placement = placement_of(s);
  slicer::progress_phase(s.progress, "reading the mesh");
  slicer::Mesh file;
  if (objects) {
    *objects = read_slice_objects(s);
    std::vector<slicer::Mesh> meshes;
    for (const SliceObject& o : *objects) meshes.push_back(o.mesh);
    file = slicer::merge_meshes(meshes);
  } else {
    file = slicer::read_mesh_file(s.part);
  }
  placed.setIdentity();
  if (s.up == "y") {
    for (slicer::Vec3& v : file.vertices_mm) v = slicer::Vec3(v.x(), -v.z(), v.y());
    placed.linear() << 1, 0, 0, 0, 0, -1, 0, 1, 0;
  }
  Eigen::Affine3d step;
  slicer::Mesh raw = slicer::place_mesh(std::move(file), placement, &step);
  placed = step * placed;
  scale = s.scale;
  if (!s.scale_to_fit.empty()) scale = scale_to_fit(slicer::bounds(raw).size_mm(), s.scale_to_fit);
  if (scale != 1.0) {
    raw = slicer::place_mesh(std::move(raw), {scale, slicer::Vec3::Zero(), placement.place}, &step);
    placed = step * placed;
  }
  slicer::progress_phase(s.progress, s.repair ? "checking and repairing the mesh" : "checking the mesh");
  slicer::PreparedMesh part;
  if (objects) {
    part = prepare_objects(raw, *objects, {s.repair, s.strict}, placement.place, &step);
  } else {
    part = slicer::prepare_mesh(raw, {s.repair, s.strict}, "mesh = " + s.part);
    // Repairs may add triangles at the extremes: rest the part on the bed again.
    part.mesh = slicer::place_mesh(part.mesh, {1.0, slicer::Vec3::Zero(), placement.place}, &step);
  }
  placed = step * placed;
  return part;
}

// Before any slicing work: the part's bounding box against the build volume (the planner
// checks every move again at the end).
void check_part_fits(const slicer::Mesh& mesh, const machines::MachineProfile& m) {
  const slicer::Vec3 size = slicer::bounds(mesh).size_mm();
  const std::string part = size_text(size);
  const auto& v = m.volume;
  if (v.kind == machines::KinematicsKind::Delta) {
    double r = 0.0;  // the part frame's origin sits on the build plate's centre
    for (const slicer::Vec3& p : mesh.vertices_mm) r = std::max(r, p.head<2>().norm());
    r = std::ceil(r * 10.0) / 10.0;
    if (r > v.radius_mm + slicer::kBoundsSlackMm || size.z() > v.height_mm) {
      throw InputError("slice: the part (" + part + ", reaching " + slicer::short_number(r) +
                       " mm from the centre) does not fit " + m.name + " (radius " +
                       slicer::short_number(v.radius_mm) + " mm, height " +
                       slicer::short_number(v.height_mm) + " mm)");
    }
    return;
  }
  const slicer::Vec3 room = v.max_mm - v.min_mm;
  if ((size.array() > room.array() + slicer::kBoundsSlackMm).any()) {
    throw InputError("slice: the part (" + part + ") does not fit " + m.name + " (" +
                     slicer::short_number(room.x()) + " x " + slicer::short_number(room.y()) +
                     " x " + slicer::short_number(room.z()) + " mm)");
  }
}

nlohmann::json slice_parameters(const SliceSettings& s, const patterns::RegionPattern& p) {
  nlohmann::json j = p.values;
  if (!s.part.empty()) j["part"] = s.part_name.empty() ? s.part : s.part_name;
  for (const SlicePart& p : s.parts) j["parts"].push_back(p.path + ":" + std::to_string(p.tool));
  if (s.tool_order != "fewest-changes") j["tool-order"] = s.tool_order;
  if (!s.onto.empty()) j["onto"] = s.onto;
  j["pattern"] = s.pattern;
  j["perimeters"] = s.perimeters;
  j["mesh-units"] = s.mesh_units;
  j["place"] = s.place;
  j["rotate"] = s.rotate;
  j["repair"] = s.repair;
  if (s.strict) j["strict"] = true;
  if (s.scale != 1.0) j["scale"] = s.scale;
  if (!s.scale_to_fit.empty()) j["scale-to-fit"] = s.scale_to_fit;
  if (s.up != "z") j["up"] = s.up;
  return j;
}

// Layers for a part `height_mm` tall; throws InputError when the layers, or the pattern
// segments to clip over all of them, exceed the work bounds.
int layer_count(const patterns::RegionPattern& pattern, double height_mm,
                const slicer::Vec2& half) {
  const double layers_exact = height_mm / pattern.layer_height_mm;
  if (layers_exact > kMaxSliceLayers) {
    throw InputError("slice.layer-height = " + slicer::short_number(pattern.layer_height_mm) +
                     ": the part (" + slicer::short_number(height_mm) +
                     " mm tall) would need more than " + std::to_string(kMaxSliceLayers) +
                     " layers");
  }
  const int layers = std::max(1, static_cast<int>(std::lround(layers_exact)));
  double segments = 0.0;
  for (const auto& line : patterns::pattern_lines(pattern, 0, half)) {
    segments += static_cast<double>(line.points.size());
  }
  if (segments * layers > kMaxSliceSegments) {
    throw InputError("slice: " + std::to_string(layers) + " layers of " +
                     slicer::short_number(segments) +
                     " pattern segments each is more work than allowed (" +
                     slicer::short_number(kMaxSliceSegments) +
                     " segments in all); use a coarser pattern or a larger layer height");
  }
  return layers;
}

// A part no layer can hold, or no bead can fill anywhere, is refused (no empty file).
void check_printable(const std::vector<patterns::PartFill>& fills, const slicer::Vec3& size,
                     const patterns::RegionPattern& p) {
  const double r = p.nozzle_mm / 2.0;
  for (const patterns::PartFill& fill : fills) {
    for (const slicer::Region& layer : fill.layers) {
      if (!slicer::offset_region(layer, -r).empty()) return;
    }
  }
  throw InputError("slice.nozzle = " + slicer::short_number(p.nozzle_mm) + ": the part (" +
                   size_text(size) + ") is narrower than one bead everywhere; scale it up " +
                   "(--scale, --scale-to-fit) or use a finer nozzle");
}

// A slice that deposits nothing is refused (exit 2, no file): the pattern left no piece long
// enough in any layer (pieces shorter than a nozzle, or four for a lattice, are left out) and
// no perimeter was asked for.
void check_not_empty(const post::Produced& produced, const SliceSettings& s,
                     const slicer::Vec3& size, const patterns::RegionPattern& p) {
  const nlohmann::json& totals = produced.report.at("totals");
  if (totals.value("deposit_length_mm", 0.0) > 0.0) return;
  throw InputError("slice: every layer is empty: no " + s.pattern +
                   " strand fits in any of the " +
                   std::to_string(totals.value("layers", 0)) +
                   " layers of the part (" + size_text(size) + ") with the " +
                   slicer::short_number(p.nozzle_mm) +
                   " mm nozzle; scale it up (--scale, --scale-to-fit) or use a finer pattern or "
                   "nozzle" + (s.perimeters == 0 ? ", or add --perimeters" : ""));
}

std::vector<std::string> contour_notes(const slicer::ContourStats& c) {
  std::vector<std::string> out;
  if (c.gaps_closed > 0) {
    out.push_back("mesh: " + std::to_string(c.gaps_closed) +
                  " gap(s) closed in the contours (widest " + mm_text(c.widest_gap_mm) + " mm)");
  }
  if (c.wide_gaps_closed > 0) {
    out.push_back("mesh: " + std::to_string(c.wide_gaps_closed) +
                  " open contour(s) closed across a gap wider than " +
                  slicer::short_number(slicer::kMaxContourGapMm) + " mm");
  }
  if (c.reversed_segments > 0) {
    out.push_back("mesh: " + std::to_string(c.reversed_segments) +
                  " contour segment(s) of flipped triangles followed backwards");
  }
  if (c.dropped_pieces > 0) {
    out.push_back("mesh: " + std::to_string(c.dropped_pieces) +
                  " open contour piece(s) of fewer than 3 points left out");
  }
  return out;
}

// The part filled layer by layer.
SliceResult slice_part(const SliceSettings& s, const patterns::GeneratorSpec& g,
                       const machines::MachineProfile& machine) {
  SliceResult r;
  std::vector<SliceObject> objects;  // a slice by objects (jobs/slice_objects.h), or none
  const bool by_object = slices_objects(s);
  Eigen::Affine3d placed;
  r.part = load_part(s, r.scale, by_object ? &objects : nullptr, placed);
  if (by_object) check_object_tools(objects, machine);
  const slicer::Box3 box = slicer::bounds(r.part.mesh);
  const slicer::Vec3 size = box.size_mm();
  if (s.on_part_size) s.on_part_size(size);
  check_part_fits(r.part.mesh, machine);
  const slicer::Vec2 half(std::max(std::abs(box.min_mm.x()), std::abs(box.max_mm.x())),
                          std::max(std::abs(box.min_mm.y()), std::abs(box.max_mm.y())));
  const patterns::RegionPattern pattern = patterns::region_pattern(g, s.pattern_values, half);
  if (size.z() < pattern.layer_height_mm) {
    throw InputError("slice.layer-height = " + slicer::short_number(pattern.layer_height_mm) +
                     ": the part (" + size_text(size) + ") is thinner than one layer (nozzle " +
                     slicer::short_number(pattern.nozzle_mm) + " mm); scale it up (--scale, " +
                     "--scale-to-fit) or use a finer nozzle and layer");
  }
  const int layers = layer_count(pattern, size.z(), half);
  slicer::ContourStats contours;
  slicer::progress_phase(s.progress, "slicing");
  // The part's layers, or each object's apart.
  std::vector<std::vector<slicer::Region>> cut;
  if (!by_object) cut.push_back(cut_layers(r.part.mesh, pattern.layer_height_mm, layers, &contours));
  for (const SliceObject& o : objects) cut.push_back(cut_layers(o.mesh, pattern.layer_height_mm, layers, &contours));
  if (by_object) check_objects_apart(objects, cut, pattern.layer_height_mm);
  // Thin features first: their centre-line beads print what no bead of the fill reaches.
  std::vector<patterns::PartFill> fills(cut.size());
  patterns::PartThinBeads thin;
  for (std::size_t i = 0; i < cut.size(); ++i) {
    fills[i].layers = std::move(cut[i]);
    patterns::PartThinBeads t = thin_features_in_parallel(fills[i].layers, pattern.nozzle_mm, pattern.layer_height_mm);
    thin.count += t.count;
    thin.length_mm += t.length_mm;
    fills[i].extra_strokes = std::move(t.per_layer);
  }
  if (thin.count == 0) check_printable(fills, size, pattern);
  r.notes = r.part.defects;
  for (const auto& n : contour_notes(contours)) r.notes.push_back(n);
  nlohmann::json skipped = nlohmann::json::array();
  for (std::size_t i = 0; i < fills.size(); ++i) {
    for (const auto& n : skip_thin_walls(fills[i].layers, pattern, skipped)) r.notes.push_back(n);
    fills[i].half_extent_mm = half;
    fills[i].volume_mm3 = slicer::signed_volume_mm3(by_object ? objects[i].mesh : r.part.mesh);
    fills[i].perimeters = s.perimeters;
  }
  // A layer with material its fill leaves empty (a rounded top narrower than a bead) gets
  // a centre bead: every layer with material deposits.
  const FillCompletion complete = [&](const slicer::Region& region, patterns::LayerFill& f) {
    if (f.strokes.empty() && has_material(region, pattern.nozzle_mm)) {
      f.strokes = material_beads(region, pattern.nozzle_mm, pattern.layer_height_mm);
    }
  };
  // Each layer is filled, planned and written before the next (postprocess/plan/produce.h);
  // the file is kept in memory: the slice previews and checks read the finished text.
  std::unique_ptr<patterns::PartFillSource> filled;
  if (by_object) {
    std::vector<int> tools;
    for (const SliceObject& o : objects) tools.push_back(o.tool);
    filled = objects_fill_layers(std::move(fills), tools, pattern, s.tool_order, complete);
  } else {
    filled = patterns::part_fill_layers(std::move(fills[0]), pattern);
  }
  slicer::Toolpath& record = filled->record;
  record.parameters = slice_parameters(s, pattern);
  record.derived["size_mm"] = {size.x(), size.y(), size.z()};
  if (r.scale != 1.0) record.derived["scale"] = r.scale;
  record.derived["mesh_triangles"] = r.part.mesh.triangles.size();
  record.derived["mesh_repairs"] = r.part.changes;
  record.derived["mesh_notes"] = r.notes;
  record.derived["skipped_regions"] = skipped;
  record.derived["thin_beads"] = {{"count", thin.count},
                                  {"length_mm", std::round(thin.length_mm * 1000.0) / 1000.0}};
  for (const SliceObject& o : objects) record.derived["objects"].push_back({{"name", o.name}, {"tool", o.tool}});
  post::ProduceOptions po;
  po.gcode_path = s.output;
  po.viewer_e = s.viewer_e;
  po.progress = s.progress;
  po.phase = "filling layers, planning and writing G-code";
  po.keep_program = s.arc_tolerance_mm > slicer::kDefaultArcToleranceMm;  // vet_produced reads it
  // Filled a few layers ahead on every thread, planned and written in layer order.
  post::PlanOptions options = post::plan_options_from(record, s.arc_tolerance_mm);
  if (!s.tools.is_null() && !tools_by_object(s.tools)) {
    options.tools = tools_for(s.tools, machine, "slice.tools");
  }
  post::LayerProducer producer(record, filled->layer_count(), machine, options, po);
  SliceLayerStats stats(pattern.nozzle_mm);
  std::function<void(std::size_t, patterns::LayerFill&)> complete_layer;  // objects complete their own
  if (!by_object) complete_layer = [&](std::size_t k, patterns::LayerFill& f) { complete(filled->region(k), f); };
  produce_filled(
      *filled, producer,
      [&](std::size_t k, const slicer::Layer& layer) { stats.add(k, filled->region(k), layer); },
      complete_layer);
  stats.write(record.derived);
  r.produced = producer.finish();
  if (!s.tools.is_null()) r.produced.report["tools"] = s.tools;
  r.produced.report["mesh_placement"] = mesh_placement_json("part", slice_inputs(s), placed, machine);
  check_not_empty(r.produced, s, size, pattern);
  r.toolpath = std::move(record);  // the layers went as they were written
  return r;
}

// The generator's specimen draped over the substrate (conformal, 3-axis).
SliceResult produce_onto(const SliceSettings& s, const patterns::GeneratorSpec& g,
                         const machines::MachineProfile& machine) {
  SliceResult r;
  slicer::progress_phase(s.progress, "generating");
  r.toolpath = g.generate(slicer::resolve_params(g.table(), s.pattern_values));
  slicer::progress_phase(s.progress, "reading the substrate");
  Eigen::Affine3d placed;
  const slicer::Mesh substrate =
      slicer::place_mesh(slicer::read_mesh_file(s.onto), placement_of(s), &placed);
  const slicer::MeshSurface surface(substrate, s.onto);
  post::PlanOptions options = post::plan_options_from(r.toolpath, s.arc_tolerance_mm);
  if (!s.tools.is_null()) {
    options.tools = tools_for(s.tools, machine, "slice.tools");
  }
  slicer::progress_phase(s.progress, "draping");
  slicer::MotionProgram program = post::plan_draped(r.toolpath, surface, machine, options);
  r.toolpath.parameters["onto"] = s.onto;
  r.toolpath.parameters["mesh-units"] = s.mesh_units;
  r.toolpath.parameters["rotate"] = s.rotate;
  r.toolpath.derived["substrate"] = surface.describe();
  r.produced = post::produce_program(r.toolpath, std::move(program), machine, options, s.output,
                                     s.viewer_e, s.progress);
  r.produced.report["mesh_placement"] = mesh_placement_json("substrate", {s.onto}, placed, machine);
  r.part.mesh = substrate;  // drawn under the path by --preview
  return r;
}

}  // namespace

SliceResult produce_slice(const SliceSettings& s) {
  const patterns::GeneratorSpec* g = patterns::find_generator(s.pattern);
  if (!g) throw InputError("slice.pattern = " + s.pattern + ": must be one of " + pattern_names());
  check_settings(s);
  if (!s.parts.empty() && (!s.part.empty() || !s.onto.empty())) {
    throw InputError("--part: give every part as --part FILE:TOOL, without PART or --onto");
  }
  if (s.parts.empty() && s.part.empty() == s.onto.empty()) {
    throw InputError(
        "slice: give a part to fill or --onto SUBSTRATE to lay the pattern on, not both");
  }
  if (!s.onto.empty() && tools_by_object(s.tools)) {
    throw InputError("slice.tools = objects: tools by object are for a part's objects, not --onto");
  }
  const machines::MachineProfile machine = machines::load_profile(s.machine);
  if (machine.plotter.enabled) {
    throw InputError("machine = " + s.machine +
                     ": a pen plotter; slice needs a printer profile (strand machines lists them)");
  }
  if (machine.robot.enabled || machine.rotary.enabled) {
    // Parts and substrate meshes print on 3-axis machines; the robot and rotary planners
    // turn a cylinder (the generators' --substrate cylinder).
    throw InputError("machine = " + s.machine + " (" +
                     (machine.robot.enabled ? "robot-holds-substrate" : "rotary") +
                     "): slice and --onto need a 3-axis printer (a delta or Cartesian profile)");
  }
  // The job's threads: its parallel loops run in this arena (a sweep's own parallel loop
  // around it shares the cores).
  // (automatic is a static const without a definition in the library: read its value, never
  // bind a reference to it, or clang's -O1 sanitizer build fails to link.)
  const int arena_threads = s.threads ? *s.threads : int{tbb::task_arena::automatic};
  tbb::task_arena arena(arena_threads);
  SliceResult out = arena.execute(
      [&] { return s.onto.empty() ? slice_part(s, *g, machine) : produce_onto(s, *g, machine); });
  slicer::progress_phase(s.progress, "checking");
  vet_produced(out.produced, machine, s.arc_tolerance_mm);
  return out;
}

}  // namespace strand::jobs
