// `strand preview FILE.gcode -o OUT`: any G-code, through the parser, drawn as .png, .svg,
// .html (the 3D viewer with its data, self-contained) or .glb (3D), chosen by OUT's extension.
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>

#include "cli/param_flags.h"
#include "cli/commands.h"
#include "cli/output_path.h"
#include "cli/progress_bar.h"
#include "jobs/curved_preview.h"
#include "jobs/slice_placement.h"
#include "postprocess/inspect/curved_files.h"
#include "postprocess/inspect/gcode_parser.h"
#include "postprocess/preview/preview_gltf.h"
#include "postprocess/preview/viewer_html.h"
#include "postprocess/preview/preview_image.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"
#include "slicer/json_input.h"
#include "slicer/params.h"
#include "slicer/tolerances.h"
#include "slicer/unit_values.h"

namespace strand::cli {

using jobs::curved_file_scene;

namespace {

struct PreviewArgs {
  std::string input;
  std::string output;
  int layer = -1;
  std::string colour = "feature";
  std::string view = "both";
  bool travel = false;
  bool lines = false;
  bool marks = false;
  std::string size = "1200x700";
  std::string mesh_from;  // a `strand slice --report` file: its part drawn under the paths (.html)
  double arc_tolerance_mm = slicer::kDefaultArcToleranceMm;
};

post::ImageOptions image_options(const PreviewArgs& a) {
  post::ImageOptions o;
  if (a.colour != "feature" && a.colour != "layer") throw InputError("--colour = " + a.colour + ": must be feature or layer");
  o.colouring = a.colour == "layer" ? post::PreviewColouring::Layer : post::PreviewColouring::Feature;
  if (a.view == "top") {
    o.view = post::PreviewView::Top;
  } else if (a.view == "iso") {
    o.view = post::PreviewView::Iso;
  } else if (a.view == "both") {
    o.view = post::PreviewView::Both;
  } else {
    throw InputError("--view = " + a.view + ": must be top, iso or both");
  }
  // "1200x700", "1200 x 700 px": whole pixels, at most 100000 a side (the renderer's own
  // bound on the area follows).
  const slicer::UnitValues size = slicer::parse_quantities(a.size, "px", 'x');
  const auto whole = [](double v) { return v >= 1.0 && v <= 100000.0 && v == std::floor(v); };
  if (!size.ok() || size.values.size() != 2 || !whole(size.values[0]) || !whole(size.values[1])) {
    throw InputError("--size = " + a.size + ": must be WxH in whole pixels, each in [1, 100000], e.g. 1200x700" +
                     (size.unit_problem.empty() ? "" : " (" + size.unit_problem + ")"));
  }
  o.width_px = static_cast<int>(size.values[0]);
  o.height_px = static_cast<int>(size.values[1]);
  o.layer = a.layer;
  o.travel = a.travel;
  return o;
}

// The 3D viewer (viewer_html.h): G-code read layer by layer into its blocks, a curved file
// through its scene on the substrate.
int write_viewer(const PreviewArgs& a, const std::string& text, bool curved, PhaseProgress* progress) {
  const std::string name = std::filesystem::path(a.input).filename().string();
  slicer::progress_phase(progress, "parsing");
  post::ViewerData data;
  try {
    data = curved ? post::viewer_data_from_scene(curved_file_scene(a.input, text, a.arc_tolerance_mm), name)
                  : post::viewer_data_from_gcode(text, nullptr, a.arc_tolerance_mm, name);
  } catch (const InputError& e) {
    const std::string what = e.what();
    throw InputError(what.rfind("input = ", 0) == 0 ? what : "input = " + a.input + ": " + what);
  }
  if (!a.mesh_from.empty()) {  // the part a slice recorded, placed as it was sliced
    const nlohmann::json report = slicer::parse_json(slicer::read_file(a.mesh_from), "mesh-from = " + a.mesh_from);
    if (!report.is_object() || !report.contains("mesh_placement"))
      throw InputError("mesh-from = " + a.mesh_from + ": no mesh_placement (not a report of strand slice --report)");
    jobs::PlacedMesh m = jobs::placed_mesh_from(report["mesh_placement"], "");
    if (!m.note.empty()) std::cerr << "strand: " << m.note << "\n";
    (report["mesh_placement"].value("role", "") == "substrate" ? data.substrate : data.part) = std::move(m.mesh);
    data.part_note = m.note;
  }
  slicer::progress_phase(progress, "drawing");
  slicer::OutputFiles out;
  out.protect_input(a.input);
  out.stage(a.output, post::render_viewer_html(data, name));
  out.commit();
  if (progress) progress->finish();
  std::size_t segments = 0;
  for (const auto& l : data.layers) segments += l.segments;
  std::cout << "preview " << a.input << " -> " << a.output << " (" << data.layers.size() << " layers, "
            << segments << " segments, 3D viewer)\n";
  return 0;
}

int run(PreviewArgs a) {
  if (a.output.empty()) a.output = output_from_input(a.input, "-preview.png");  // part.gcode -> part-preview.png
  a.colour = slicer::match_choice(a.colour, {"feature", "layer"}).value_or(a.colour);
  a.view = slicer::match_choice(a.view, {"top", "iso", "both"}).value_or(a.view);
  const std::string ext = std::filesystem::path(a.output).extension().string();
  if (ext != ".png" && ext != ".svg" && ext != ".html" && ext != ".glb") {
    throw InputError("--output = " + a.output + ": extension must be .png, .svg, .html or .glb");
  }
  if (!(a.arc_tolerance_mm >= post::kMinFlattenToleranceMm && a.arc_tolerance_mm <= 1.0)) {
    throw InputError("arc-tolerance = " + slicer::short_number(a.arc_tolerance_mm) +
                     ": must be in [0.001, 1] (mm)");
  }
  const auto progress = command_progress("preview", a.marks ? 4 : 3);
  slicer::progress_phase(progress.get(), "reading");
  const std::string gcode = slicer::read_file(a.input);
  // A pose CSV or rotary G-code is drawn on its workpiece (the cylinder's axis along x, its
  // u = 0 line on top); checks marks are for flat files.
  const bool curved = a.input.ends_with(".csv") || post::is_rotary_gcode(gcode);
  if (curved && a.marks)
    throw InputError("marks: only for flat G-code (a curved file is checked with strand check)");
  if (ext == ".html") return write_viewer(a, gcode, curved, progress.get());
  if (!a.mesh_from.empty()) throw InputError("mesh-from = " + a.mesh_from + ": only for the 3D viewer (-o x.html)");
  post::ParsedGcode parsed;
  slicer::progress_phase(progress.get(), "parsing");
  try {  // errors name the file as strand check names it
    if (!curved) parsed = post::parse_gcode(gcode);
  } catch (const InputError& e) {
    throw InputError("input = " + a.input + ": " + e.what());
  }
  const post::PreviewScene scene =
      curved ? curved_file_scene(a.input, gcode, a.arc_tolerance_mm)
             : post::preview_scene(parsed.program, a.arc_tolerance_mm, parsed.pen_colours);
  if (scene.paths.empty()) throw InputError("input = " + a.input + ": no moves to draw (is it G-code?)");
  post::ImageOptions o = image_options(a);
  if (a.marks) {
    slicer::progress_phase(progress.get(), "checking");
    post::CheckOptions check;
    check.arc_tolerance_mm = a.arc_tolerance_mm;
    check.touch_mm = slicer::kGcodeResolutionMm;
    o.marks = post::marks_from(post::check_parsed(parsed, check));
  }
  slicer::progress_phase(progress.get(), "drawing");
  std::string bytes;
  if (ext == ".png") bytes = post::render_png(scene, o);
  if (ext == ".svg") bytes = post::render_svg(scene, o);
  if (ext == ".glb") bytes = post::render_glb(scene, {.tubes = !a.lines});
  slicer::OutputFiles out;
  out.protect_input(a.input);
  out.stage(a.output, bytes);
  out.commit();
  if (progress) progress->finish();
  std::cout << "preview " << a.input << " -> " << a.output << " (" << scene.layer_z_mm.size() << " layers, "
            << scene.paths.size() << " paths)\n";
  return 0;
}

}  // namespace

void add_preview_command(CLI::App& app, Action& action) {
  auto a = std::make_shared<PreviewArgs>();
  CLI::App* sub = app.add_subcommand("preview", "draw any G-code file as .png, .svg, .html or .glb (by -o's extension)");
  sub->add_option("gcode", a->input, "G-code file")->required();
  sub->add_option("-o,--output", a->output,
                  "preview file: .png, .svg, .html or .glb (default: GCODE's name with -preview.png)");
  sub->add_option("--layer", a->layer, "only this layer (0-based, as ;LAYER:n; png/svg; default all)")
      ->check(CLI::Range(0, 100000000));
  sub->add_option("--colour", a->colour, "colour by feature or layer (png/svg; default feature)");
  sub->add_option("--view", a->view, "top, iso or both side by side (png/svg; default both)");
  sub->add_flag("--travel", a->travel, "also draw travel moves (png/svg)");
  sub->add_flag("--marks", a->marks, "circle crossings (red) and touches (orange) found by strand check (png/svg)");
  sub->add_option("--mesh-from", a->mesh_from,
                  "html: draw the part a `strand slice --report` file records (its mesh file, placed as sliced)");
  sub->add_flag("--lines", a->lines, "glb: strands as lines instead of tubes");
  sub->add_option("--size", a->size, "image size WxH in pixels (png/svg; default 1200x700)");
  add_quantity_option(sub, "--arc-tolerance", a->arc_tolerance_mm, "mm", "chord error when drawing G2/G3 arcs [mm] (default 0.01)");
  sub->callback([&action, a] { action = [a] { return run(*a); }; });
}

}  // namespace strand::cli
