// The slice pipeline: read, check, place, slice, fill, produce.
#include "cli/slice_job.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>

#include "jobs/job_runner.h"
#include "machines/profile.h"
#include "patterns/region_fill.h"
#include "patterns/registry.h"
#include "postprocess/plan/drape.h"
#include "slicer/input_error.h"
#include "slicer/mesh_io.h"
#include "slicer/mesh_slicer.h"
#include "slicer/mesh_surface.h"
#include "slicer/params.h"
#include "slicer/unit_values.h"

namespace strand::cli {

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

slicer::PreparedMesh load_part(const SliceSettings& s, double& scale) {
  if (s.up != "z" && s.up != "y") throw InputError("slice.up = " + s.up + ": must be z or y");
  const std::string ext = std::filesystem::path(s.part).extension().string();
  if (s.up == "y" && (ext == ".gltf" || ext == ".glb" || ext == ".GLTF" || ext == ".GLB")) {
    throw InputError("slice.up = y: glTF is +Y up by definition and is turned to +Z already");
  }
  if ((ext == ".3mf" || ext == ".3MF") && s.mesh_units != "mm") {
    throw InputError("slice.mesh-units = " + s.mesh_units +
                     ": a 3MF file states its own unit (use --scale to resize it)");
  }
  check_scale(s.scale);
  if (!s.scale_to_fit.empty() && s.scale != 1.0) {
    throw InputError("slice.scale-to-fit = " + s.scale_to_fit +
                     ": give --scale or --scale-to-fit, not both");
  }
  const slicer::MeshPlacement placement = placement_of(s);
  slicer::progress_phase(s.progress, "reading the mesh");
  slicer::Mesh file = slicer::read_mesh_file(s.part);
  if (s.up == "y") {
    for (slicer::Vec3& v : file.vertices_mm) v = slicer::Vec3(v.x(), -v.z(), v.y());
  }
  slicer::Mesh raw = slicer::place_mesh(std::move(file), placement);
  scale = s.scale;
  if (!s.scale_to_fit.empty()) scale = scale_to_fit(slicer::bounds(raw).size_mm(), s.scale_to_fit);
  if (scale != 1.0)
    raw = slicer::place_mesh(std::move(raw), {scale, slicer::Vec3::Zero(), placement.place});
  slicer::progress_phase(s.progress, s.repair ? "checking and repairing the mesh" : "checking the mesh");
  slicer::PreparedMesh part = slicer::prepare_mesh(raw, {s.repair, s.strict}, "mesh = " + s.part);
  // Repairs may add triangles at the extremes: rest the part on the bed again.
  part.mesh = slicer::place_mesh(part.mesh, {1.0, slicer::Vec3::Zero(), placement.place});
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
  if (!s.part.empty()) j["part"] = s.part;
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
void check_printable(const std::vector<slicer::Region>& layers, const slicer::Vec3& size,
                     const patterns::RegionPattern& p) {
  const double r = p.nozzle_mm / 2.0;
  for (const slicer::Region& layer : layers) {
    if (!slicer::offset_region(layer, -r).empty()) return;
  }
  throw InputError("slice.nozzle = " + slicer::short_number(p.nozzle_mm) + ": the part (" +
                   size_text(size) + ") is narrower than one bead everywhere; scale it up " +
                   "(--scale, --scale-to-fit) or use a finer nozzle");
}

// Strips of a layer no bead reaches (more than 4 nozzle^2, with the layers below and above
// covering them too: a wall, not a curved part's rim) are taken out of the layer, and said.
std::vector<std::string> skip_thin_walls(std::vector<slicer::Region>& layers,
                                         const patterns::RegionPattern& p,
                                         nlohmann::json& skipped) {
  const double d = p.nozzle_mm, r = d / 2.0, h = p.layer_height_mm;
  std::vector<slicer::Region> lost(layers.size());
  for (std::size_t k = 0; k < layers.size(); ++k) {
    const slicer::Region reached = slicer::offset_region(slicer::offset_region(layers[k], -r), r);
    for (const auto& piece : slicer::region_difference(layers[k], reached)) {
      const double area = slicer::area_mm2(piece);
      if (area <= 4.0 * d * d) continue;
      bool wall = true;
      for (const std::size_t j : {k - 1, k + 1}) {  // k - 1 wraps for k = 0: not a layer
        wall = wall && j < layers.size() &&
               slicer::area_mm2(slicer::region_intersection({piece}, layers[j])) > area / 2;
      }
      if (wall) lost[k].push_back(piece);
    }
  }
  std::vector<std::string> notes;
  for (std::size_t k = 0; k < layers.size();) {
    if (lost[k].empty()) {
      ++k;
      continue;
    }
    std::size_t end = k;
    double area = 0.0;
    slicer::Region first = lost[k];
    for (; end < layers.size() && !lost[end].empty(); ++end) {
      area += slicer::area_mm2(lost[end]);
      layers[end] = slicer::region_difference(layers[end], lost[end]);
    }
    const auto [lo, hi] = slicer::region_bounds(first);
    const slicer::Vec2 c = (lo + hi) / 2.0;
    const double z0 = static_cast<double>(k) * h, z1 = static_cast<double>(end) * h;
    notes.push_back("skipped " + mm_text(area) + " mm2 too thin for the " +
                    slicer::short_number(d) + " mm nozzle near (" + mm_text(c.x()) + ", " +
                    mm_text(c.y()) + "), z " + mm_text(z0) + " to " + mm_text(z1) + " mm");
    skipped.push_back(
        {{"area_mm2", std::round(area * 1000.0) / 1000.0},
         {"near_mm", {std::round(c.x() * 1000.0) / 1000.0, std::round(c.y() * 1000.0) / 1000.0}},
         {"z_mm", {std::round(z0 * 1000.0) / 1000.0, std::round(z1 * 1000.0) / 1000.0}}});
    k = end;
  }
  return notes;
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
  r.part = load_part(s, r.scale);
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
  patterns::PartFill fill;
  slicer::ContourStats contours;
  slicer::progress_phase(s.progress, "slicing");
  fill.layers = slicer::slice_layers(r.part.mesh, pattern.layer_height_mm, layers, &contours);
  check_printable(fill.layers, size, pattern);
  r.notes = r.part.defects;
  for (const auto& n : contour_notes(contours)) r.notes.push_back(n);
  nlohmann::json skipped = nlohmann::json::array();
  for (const auto& n : skip_thin_walls(fill.layers, pattern, skipped)) r.notes.push_back(n);
  fill.half_extent_mm = half;
  fill.volume_mm3 = slicer::signed_volume_mm3(r.part.mesh);
  fill.perimeters = s.perimeters;
  // Each layer is filled, planned and written before the next (postprocess/plan/produce.h);
  // the file is kept in memory: the slice previews and checks read the finished text.
  const std::unique_ptr<slicer::LayerSource> filled = patterns::part_fill_layers(std::move(fill), pattern);
  slicer::Toolpath& record = filled->record;
  record.parameters = slice_parameters(s, pattern);
  record.derived["size_mm"] = {size.x(), size.y(), size.z()};
  if (r.scale != 1.0) record.derived["scale"] = r.scale;
  record.derived["mesh_triangles"] = r.part.mesh.triangles.size();
  record.derived["mesh_repairs"] = r.part.changes;
  record.derived["mesh_notes"] = r.notes;
  record.derived["skipped_regions"] = skipped;
  post::ProduceOptions po;
  po.gcode_path = s.output;
  po.viewer_e = s.viewer_e;
  po.progress = s.progress;
  po.phase = "filling layers, planning and writing G-code";
  po.keep_program = s.arc_tolerance_mm > slicer::kDefaultArcToleranceMm;  // vet_produced reads it
  r.produced = post::produce_layers(*filled, machine, post::plan_options_from(record, s.arc_tolerance_mm), po);
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
  const slicer::Mesh substrate =
      slicer::place_mesh(slicer::read_mesh_file(s.onto), placement_of(s));
  const slicer::MeshSurface surface(substrate, s.onto);
  const post::PlanOptions options = post::plan_options_from(r.toolpath, s.arc_tolerance_mm);
  slicer::progress_phase(s.progress, "draping");
  slicer::MotionProgram program = post::plan_draped(r.toolpath, surface, machine, options);
  r.toolpath.parameters["onto"] = s.onto;
  r.toolpath.parameters["mesh-units"] = s.mesh_units;
  r.toolpath.parameters["rotate"] = s.rotate;
  r.toolpath.derived["substrate"] = surface.describe();
  r.produced = post::produce_program(r.toolpath, std::move(program), machine, options, s.output,
                                     s.viewer_e, s.progress);
  r.part.mesh = substrate;  // drawn under the path by --preview
  return r;
}

}  // namespace

double scale_to_fit(const slicer::Vec3& size_mm, const std::string& box) {
  // "30x30x30", "3 x 3 x 3 cm", "30mm x 30mm x 1in" (slicer/unit_values.h).
  const slicer::UnitValues given = slicer::parse_quantities(box, "mm", 'x');
  const std::vector<double>& v = given.values;
  if (!given.ok() || v.size() != 3 || !std::all_of(v.begin(), v.end(), [](double d) { return d > 0.0 && d <= 100000.0; })) {
    throw InputError("slice.scale-to-fit = " + box + ": must be WxDxH in mm, each in (0, 100000], e.g. 30x30x30" +
                     (given.unit_problem.empty() ? "" : " (" + given.unit_problem + ")"));
  }
  double f = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    if (size_mm[k] > 0.0) f = std::min(f, v[static_cast<std::size_t>(k)] / size_mm[k]);
  }
  if (!std::isfinite(f)) throw InputError("slice.scale-to-fit = " + box + ": the part has no size");
  return f;
}

slicer::Vec3 rotation_from_text(const std::string& text) {
  // "90,0,0", "0,0,1.5708rad", "0, 0, 45 deg" (slicer/unit_values.h).
  const slicer::UnitValues given = slicer::parse_quantities(text, "deg", ',');
  const std::vector<double>& v = given.values;
  if (!given.ok() || v.size() != 3 || !std::all_of(v.begin(), v.end(), [](double d) { return std::abs(d) <= 360.0; })) {
    throw InputError("slice.rotate = " + text + ": must be X,Y,Z in degrees, each in [-360, 360]" +
                     (given.unit_problem.empty() ? "" : " (" + given.unit_problem + ")"));
  }
  return {v[0], v[1], v[2]};
}

SliceResult produce_slice(const SliceSettings& s) {
  const patterns::GeneratorSpec* g = patterns::find_generator(s.pattern);
  if (!g) throw InputError("slice.pattern = " + s.pattern + ": must be one of " + pattern_names());
  check_settings(s);
  if (s.part.empty() == s.onto.empty()) {
    throw InputError(
        "slice: give a part to fill or --onto SUBSTRATE to lay the pattern on, not both");
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
  SliceResult out = s.onto.empty() ? slice_part(s, *g, machine) : produce_onto(s, *g, machine);
  slicer::progress_phase(s.progress, "checking");
  vet_produced(out.produced, machine, s.arc_tolerance_mm);
  return out;
}

}  // namespace strand::cli
