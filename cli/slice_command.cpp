// `strand slice PART --pattern NAME [pattern flags]`: flags to SliceSettings, then the
// slice job, files written atomically, a short summary printed.
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>

#include <filesystem>

#include "cli/commands.h"
#include "cli/slice_job.h"
#include "machines/profile.h"
#include "patterns/registry.h"
#include "postprocess/inspect/gcode_parser.h"
#include "postprocess/preview/preview_file.h"
#include "slicer/mesh.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"
#include "slicer/json_input.h"
#include "slicer/params.h"

namespace strand::cli {

namespace {

struct SliceArgs {
  SliceSettings settings;
  std::map<std::string, std::string> text;  // pattern flag -> raw text
  std::map<std::string, CLI::Option*> options;
  std::string report;
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
  for (const auto& [key, opt] : a.options) {
    if (opt->count() == 0) continue;
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
  a.settings.pattern_values = pattern_values(a);
  const SliceResult r = produce_slice(a.settings);
  slicer::OutputFiles out;
  for (const std::string& input : {a.settings.part, a.settings.onto}) {
    if (!input.empty()) out.protect_input(input);
  }
  out.stage(a.settings.output, r.produced.gcode);
  if (!a.report.empty()) out.stage(a.report, slicer::dump_json(r.produced.report) + "\n");
  for (const std::string& path : a.previews) out.stage(path, preview_of(r, a.settings, path));
  out.commit();
  std::cout << r.produced.summary;
  const auto& d = r.toolpath.derived;
  if (d.contains("pattern_strands_per_layer")) {
    int most = 0;
    for (const auto& s : d.at("pattern_strands_per_layer")) most = std::max(most, s.get<int>());
    std::cout << "  pattern        " << a.settings.pattern << ": at most " << most
              << " pattern strand(s) per layer, " << a.settings.perimeters << " perimeter(s)\n";
  }
  if (d.contains("substrate")) {
    const auto& sub = d.at("substrate");
    char line[256];
    std::snprintf(line, sizeof line,
                  "%s, 3D/uv area ratio %.3f to %.3f, conformal stretch up to %.3f",
                  sub.at("uv_source").get<std::string>().c_str(),
                  sub.at("area_ratio_3d_to_uv")[0].get<double>(),
                  sub.at("area_ratio_3d_to_uv")[1].get<double>(),
                  sub.at("conformal_stretch_max").get<double>());
    std::cout << "  substrate      " << a.settings.onto << ": " << line << "\n";
  }
  for (const auto& c : r.part.changes) std::cout << "  repaired       " << c << "\n";
  return 0;
}

}  // namespace

void add_slice_command(CLI::App& app, Action& action) {
  auto a = std::make_shared<SliceArgs>();
  SliceSettings& s = a->settings;
  CLI::App* sub = app.add_subcommand(
      "slice",
      "fill a mesh (STL, OBJ, PLY, OFF, glTF) with a pattern in non-crossing strands per layer");
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
      a->options[d.key] =
          sub->add_option("--" + d.key, a->text[d.key], g.name + ": " + d.help + unit);
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
                "stitch borders, fill small holes, re-orient; the changes are reported");
  sub->add_option("--machine", s.machine,
                  "machine profile name or path (default deltawasp-2040-clay)");
  sub->add_option("-o,--output", s.output, "G-code file to write (default slice.gcode)");
  sub->add_option("--report", a->report, "write a JSON report here");
  sub->add_option("--preview", a->previews,
                  "also draw the result with the mesh under it, translucent: .png, .svg, .html "
                  "(3D orbit view) or .glb (repeatable)");
  sub->add_option("--arc-tolerance", s.arc_tolerance_mm,
                  "max chord error when arcs become G1 segments [mm] (default 0.01)");
  sub->callback([&action, a] { action = [a] { return run_slice(*a); }; });
}

}  // namespace strand::cli
