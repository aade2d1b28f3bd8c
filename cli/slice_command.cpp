// `strand slice PART --pattern NAME [pattern flags]`: flags to SliceSettings, then the
// slice job, files written atomically, a short summary printed.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>

#include "cli/param_flags.h"
#include "cli/commands.h"
#include "cli/output_path.h"
#include "cli/progress_bar.h"
#include "jobs/slice_job.h"
#include "jobs/slice_objects.h"
#include "jobs/job_runner.h"
#include "machines/profile.h"
#include "patterns/region_pattern.h"
#include "patterns/registry.h"
#include "postprocess/inspect/gcode_parser.h"
#include "postprocess/preview/preview_file.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"
#include "slicer/json_input.h"
#include "slicer/mesh.h"
#include "slicer/mesh_check.h"
#include "slicer/mesh_io.h"
#include "slicer/params.h"
#include "slicer/unit_values.h"

namespace strand::cli {

using jobs::SliceResult;
using jobs::SliceSettings;
using jobs::viewer_output_path;

namespace {

struct SliceArgs {
  SliceSettings settings;
  std::map<std::string, std::string> text;  // pattern flag -> raw text
  std::map<std::string, CLI::Option*> options;
  std::string report;
  std::string threads;                // --threads, as given (checked by the job)
  std::string tools;                  // --tools, as given (checked by the job)
  std::vector<std::string> parts;     // --part FILE:TOOL, as given
  std::vector<std::string> previews;  // .png/.svg/.html/.glb with the mesh under the path
};

// The written G-code drawn with the mesh (the part, or the substrate of --onto) under it,
// translucent, in the machine frame: the planner moved the part to the machine's part centre.
std::string preview_of(const SliceResult& r, const SliceSettings& s, const std::string& path) {
  const post::PreviewFormat format = post::preview_format(path, "slice.preview");
  const machines::MachineProfile machine = machines::load_profile(s.machine);
  post::PreviewScene scene =
      post::preview_scene(post::parse_gcode(r.produced.gcode).program, s.arc_tolerance_mm);
  scene.substrate = slicer::to_triangle_mesh(r.part.mesh);
  scene.substrate_hides_paths = !s.onto.empty();  // a filled part is drawn under its fill
  const slicer::Vec2 centre = machine.volume.part_center_mm;
  for (auto& v : scene.substrate.vertices_mm) v += slicer::Vec3(centre.x(), centre.y(), 0.0);
  post::PreviewFileOptions o;
  o.title = std::filesystem::path(s.output).filename().string();
  return post::render_preview(scene, format, o);
}

// The pattern flags the user gave, checked against the chosen generator's table.
nlohmann::json pattern_values(const SliceArgs& a) {
  const patterns::GeneratorSpec* g = patterns::find_generator(a.settings.pattern);
  nlohmann::json given = nlohmann::json::object();
  if (!g) return given;  // produce_slice names the allowed patterns
  std::vector<std::string> problems;
  for (const auto& [flag, opt] : a.options) {
    if (opt->count() == 0) continue;
    const std::string& key = flag;  // a lambda cannot capture a structured binding in clang 14
    const auto& defs = g->table().defs;
    const auto it =
        std::find_if(defs.begin(), defs.end(), [&](const auto& d) { return d.key == key; });
    if (it == defs.end()) {
      problems.push_back("slice." + key + ": not a " + g->name + " flag (see strand " + g->name +
                         " --help)");
      continue;
    }
    given[key] = slicer::parse_param_text(g->table(), *it, a.text.at(key));
  }
  if (!problems.empty()) throw InputError(problems);
  return given;
}

int run_slice(SliceArgs a) {
  SliceSettings& s = a.settings;  // choices in any case: --up Y, --place Center
  s.up = slicer::match_choice(s.up, {"z", "y"}).value_or(s.up);
  s.place = slicer::match_choice(s.place, {"center", "origin"}).value_or(s.place);
  s.mesh_units = slicer::match_choice(s.mesh_units, {"mm", "cm", "m", "in"}).value_or(s.mesh_units);
  std::vector<std::string> names;
  for (const auto& g : patterns::generators()) names.push_back(g.name);
  s.pattern = slicer::match_choice(s.pattern, names).value_or(s.pattern);
  a.settings.pattern_values = pattern_values(a);
  if (!a.threads.empty()) a.settings.threads = jobs::threads_from_text(a.threads);
  if (!a.tools.empty()) a.settings.tools = a.tools;
  for (const std::string& p : a.parts) a.settings.parts.push_back(jobs::part_from_text(p));
  if (a.settings.output.empty()) {
    std::string input = a.settings.part.empty() ? a.settings.onto : a.settings.part;
    if (input.empty() && !a.settings.parts.empty()) input = a.settings.parts.front().path;
    a.settings.output = input.empty() ? "slice.gcode" : output_from_input(input, ".gcode");
  }
  const auto progress = command_progress("slice", 6 + a.previews.size());
  a.settings.progress = progress.get();
  a.settings.on_part_size = [&progress](const slicer::Vec3& size) {
    char line[160];
    std::snprintf(line, sizeof line, "part %.3f x %.3f x %.3f mm\n", size.x(), size.y(), size.z());
    if (progress) progress->clear();
    std::cout << line << std::flush;
  };
  const SliceResult r = jobs::produce_slice(a.settings);
  slicer::OutputFiles out;
  for (const std::string& input : {a.settings.part, a.settings.onto}) {
    if (!input.empty()) out.protect_input(input);
  }
  for (const jobs::SlicePart& p : a.settings.parts) out.protect_input(p.path);
  out.stage(a.settings.output, r.produced.gcode);
  if (a.settings.viewer_e) out.stage(viewer_output_path(a.settings.output), r.produced.viewer_gcode);
  if (!a.report.empty()) out.stage(a.report, slicer::dump_json(r.produced.report) + "\n");
  for (const std::string& path : a.previews) {
    slicer::progress_phase(progress.get(), "drawing " + path);
    out.stage(path, preview_of(r, a.settings, path));
  }
  slicer::progress_phase(progress.get(), "writing files");
  out.commit();
  if (progress) progress->finish();
  std::cout << jobs::slice_summary_text(r, a.settings);
  return 0;
}

}  // namespace

void add_slice_command(CLI::App& app, Action& action) {
  auto a = std::make_shared<SliceArgs>();
  SliceSettings& s = a->settings;
  CLI::App* sub = app.add_subcommand(
      "slice",
      "fill a mesh (STL, OBJ, PLY, OFF, glTF, 3MF) with a pattern in non-crossing strands per layer");
  sub->add_option("part", s.part, "the part's mesh file (or use --onto)");
  sub->add_option(
      "--onto", s.onto,
      "lay the pattern (a whole specimen: its extent flags apply) on this substrate mesh "
      "instead: 3-axis, nozzle vertical, layers raised along z");
  sub->add_option("--pattern", s.pattern,
                  "scaffold, tetrachiral, hexachiral, missing-rib or reentrant (default scaffold)");
  // Every generator's flags, each once; the chosen pattern's own table checks them.
  for (const auto& g : patterns::generators()) {
    for (const auto& d : g.table().defs) {
      if (a->options.count(d.key)) continue;
      const std::string unit = d.unit.empty() ? "" : " [" + d.unit + "]";
      // A part's shape sets the extent: those flags are for --onto's specimen only, and
      // nothing the generator requires is required here.
      std::string help = d.help;
      if (patterns::is_extent_key(d.key)) {
        for (const char* req : {"; required", "required; "}) {
          if (const auto at = help.find(req); at != std::string::npos)
            help.erase(at, std::string(req).size());
        }
        help = "with --onto only: " + help;
      }
      a->options[d.key] = sub->add_option("--" + d.key, a->text[d.key], g.name + ": " + help + unit);
    }
  }
  sub->add_option("--perimeters", s.perimeters,
                  "closed passes along every boundary before the pattern (default 0)");
  sub->add_option("--mesh-units", s.mesh_units,
                  "units of the mesh file: mm, cm, m, in (default mm)");
  sub->add_option(
      "--place", s.place,
      "center: part centred on the machine; origin: the file's x/y origin there (default center)");
  sub->add_option("--rotate", s.rotate,
                  "rotate the part about x, then y, then z: X,Y,Z [deg] (default 0,0,0)");
  sub->add_flag("--repair", s.repair,
                "CGAL soup repair: stitch borders, fill small holes, re-orient; kept only when it "
                "makes the mesh no worse; the changes are reported");
  sub->add_flag("--strict", s.strict,
                "refuse a mesh that is open, non-manifold, misoriented or self-intersecting "
                "(default: slice the triangle soup and report what was found)");
  sub->add_option("--scale", s.scale, "uniform scale after --mesh-units (default 1)");
  sub->add_option("--scale-to-fit", s.scale_to_fit,
                  "WxDxH [mm]: the largest uniform scale at which the part fits that box");
  sub->add_option("--up", s.up, "the file's up axis: z, or y (+Y-up OBJ/STL exports; default z)");
  sub->add_option("--machine", s.machine,
                  "machine profile name or path (default deltawasp-2040-clay)");
  s.output.clear();  // run_slice names it after the part
  sub->add_option("-o,--output", s.output, "G-code file to write (default: PART's name with .gcode)");
  sub->add_flag("--viewer-e", s.viewer_e,
                "also write OUTPUT.viewer-e.gcode with E computed from the bead volume, for viewers "
                "that show only extruding moves (PrusaSlicer's); preview only, not for printing");
  sub->add_option("--report", a->report, "write a JSON report here");
  sub->add_option("--preview", a->previews,
                  "also draw the result with the mesh under it, translucent: .png, .svg, .html "
                  "(3D orbit view) or .glb (repeatable)");
  add_quantity_option(sub, "--arc-tolerance", s.arc_tolerance_mm, "mm",
                  "max chord error when arcs become G1 segments [mm] (default 0.01)");
  sub->add_option("--threads", a->threads,
                  "threads that cut, fill and plan the layers, 1 to 256 (default: every core); "
                  "the file is the same for any number");
  sub->add_option("--tools", a->tools,
                  "printheads of a multi-tool machine: by feature (wall=1,infill=0: perimeters in another ink) "
                  "or cycled per layer (layers=0,1); a 3MF's objects by build order (objects: object k in "
                  "tool k, or objects=1,0)");
  sub->add_option("--part", a->parts,
                  "FILE:TOOL, repeatable, instead of PART: several meshes in one frame (each file's own "
                  "coordinates), each filled in the ink of printhead TOOL; they may not overlap");
  sub->add_option("--tool-order", s.tool_order,
                  "printheads in each layer of a slice by objects: fewest-changes (the head already "
                  "loaded first) or given (the objects' order); default fewest-changes");
  sub->callback([&action, a] { action = [a] { return run_slice(*a); }; });
}

namespace {

struct MeshArgs {
  std::string part;
  std::string units = "mm";
  bool repair = false;
  std::string output;
  bool json = false;
};

nlohmann::json info_json(const slicer::MeshInfo& i) {
  return {{"size", {i.size.x(), i.size.y(), i.size.z()}},
          {"triangles", i.triangles},
          {"vertices", i.vertices},
          {"shells", i.shells},
          {"holes", i.holes},
          {"border_edges", i.check.border_edges},
          {"non_manifold_edges", i.check.non_manifold_edges},
          {"non_manifold_vertices", i.non_manifold_vertices},
          {"misoriented_edges", i.check.misoriented_edges},
          {"self_intersections",
           i.crossings_searched ? nlohmann::json(i.check.self_intersections) : nlohmann::json()},
          {"volume", i.volume}};
}

std::string info_text(const slicer::MeshInfo& i, const std::string& units) {
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "  size           %.3f x %.3f x %.3f %s\n"
                "  triangles      %zu (%zu vertices)\n"
                "  shells         %zu\n"
                "  holes          %zu (%zu border edges)\n"
                "  non-manifold   %zu edges, %zu vertices\n"
                "  misoriented    %zu edges\n",
                i.size.x(), i.size.y(), i.size.z(), units.c_str(), i.triangles, i.vertices,
                i.shells, i.holes, i.check.border_edges, i.check.non_manifold_edges,
                i.non_manifold_vertices, i.check.misoriented_edges);
  std::string out = buf;
  out += i.crossings_searched
             ? "  intersecting   " + std::to_string(i.check.self_intersections) +
                   " pairs of triangles\n"
             : std::string("  intersecting   not searched (the edges are not sound)\n");
  std::snprintf(buf, sizeof buf, "  volume         %.3f %s3\n", i.volume, units.c_str());
  return out + buf;
}

int run_mesh(const MeshArgs& a) {
  const double mm_per_unit = slicer::mm_per_mesh_unit("mesh.mesh-units", a.units);
  slicer::Mesh m = slicer::read_mesh_file(a.part);
  for (slicer::Vec3& v : m.vertices_mm) v *= mm_per_unit;
  if (!a.output.empty() && !a.repair) {
    throw InputError("mesh.output = " + a.output + ": -o writes the repaired mesh; add --repair");
  }
  const slicer::MeshInfo before = slicer::mesh_info(m);
  nlohmann::json j = {{"mesh", a.part}, {"info", info_json(before)}};
  std::string text = "mesh " + a.part + "\n" + info_text(before, "mm");
  if (a.repair) {
    const slicer::PreparedMesh p =
        slicer::prepare_mesh(m, slicer::PrepareOptions{true, false}, "mesh = " + a.part);
    const slicer::MeshInfo after = slicer::mesh_info(p.mesh);
    j["repairs"] = p.changes;
    j["repaired"] = info_json(after);
    text += "repaired\n";
    for (const auto& c : p.changes) text += "  repaired       " + c + "\n";
    text += info_text(after, "mm");
    if (!a.output.empty()) {
      const std::string ext = std::filesystem::path(a.output).extension().string();
      if (ext != ".stl" && ext != ".STL") {
        throw InputError("mesh.output = " + a.output + ": must end in .stl (binary STL, mm)");
      }
      slicer::OutputFiles out;
      out.protect_input(a.part);
      out.stage(a.output, slicer::binary_stl_bytes(p.mesh));
      out.commit();
      text += "wrote " + a.output + "\n";
    }
  }
  std::cout << (a.json ? slicer::dump_json(j) + "\n" : text);
  return 0;
}

}  // namespace

void add_mesh_command(CLI::App& app, Action& action) {
  auto a = std::make_shared<MeshArgs>();
  CLI::App* sub = app.add_subcommand(
      "mesh",
      "a mesh's size, triangles, shells, holes, non-manifold edges and vertices, "
      "self-intersections and volume; --repair -o FILE.stl writes it repaired");
  sub->add_option("part", a->part, "the mesh file (STL, OBJ, PLY, OFF, glTF, 3MF)")->required();
  sub->add_option("--mesh-units", a->units, "units of the mesh file: mm, cm, m, in (default mm)");
  sub->add_flag("--repair", a->repair,
                "CGAL soup repair, stitching and hole filling (kept only when no worse)");
  sub->add_option("-o,--output", a->output, "write the repaired mesh here (binary STL, mm)");
  sub->add_flag("--json", a->json, "print JSON instead of text");
  sub->callback([&action, a] { action = [a] { return run_mesh(*a); }; });
}

}  // namespace strand::cli
