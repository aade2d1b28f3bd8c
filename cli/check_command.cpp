// `strand check FILE.gcode [--machine NAME|FILE] [--rules diw|fdm|plot] [--json]
// [--svg-layer N OUT.svg]`: exit 0 when the file passes, 1 when it has problems, 2 for bad
// input. A pose CSV (FILE.csv, with the robot cell as --machine) and rotary G-code
// (;ROTARY_AXIS: header) are mapped back onto their cylinder (postprocess/inspect/pose_check.h).
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

#include "cli/param_flags.h"
#include "cli/commands.h"
#include "cli/progress_bar.h"
#include "machines/profile.h"
#include "postprocess/inspect/check.h"
#include "postprocess/inspect/check_stream.h"
#include "postprocess/inspect/mesh_pose_check.h"
#include "postprocess/inspect/pose_check.h"
#include "postprocess/preview/preview_image.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"
#include "slicer/json_input.h"
#include "slicer/params.h"
#include "slicer/tolerances.h"
#include "slicer/unit_values.h"

namespace strand::cli {

namespace {

struct CheckArgs {
  std::string file;
  std::string machine;
  std::string rules;  // empty: the default of post::read_for_check
  bool json = false;
  std::vector<std::string> svg_layer;  // {N, OUT.svg}
  double arc_tolerance_mm = slicer::kDefaultArcToleranceMm;
  std::string substrate_mesh;  // a pose CSV's mesh (default: its record, part.substrate.json)
};

bool is_csv(const std::string& file) { return file.size() > 4 && file.ends_with(".csv"); }

int parse_layer_index(const std::string& text, std::size_t layers, const std::string& file) {
  const std::string range =
      layers == 0 ? "none: " + file + " has no layers"
                  : "must be in [0, " + std::to_string(layers - 1) + "] (layers of " + file + ")";
  std::size_t used = 0;
  int n = -1;
  try {
    n = std::stoi(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || n < 0 || static_cast<std::size_t>(n) >= layers) {
    throw InputError("svg-layer = " + text + ": " + range);
  }
  return n;
}

// The top view of one layer with the check's crossings and touches circled: the preview's
// SVG drawing (`strand preview --layer N --view top --travel --marks`).
void write_svg(const post::ParsedGcode& parsed, const post::CheckReport& report,
               const CheckArgs& a) {
  post::ImageOptions o;
  o.layer = parse_layer_index(a.svg_layer[0], parsed.program.layers.size(), a.file);
  o.view = post::PreviewView::Top;
  o.travel = true;
  o.marks = post::marks_from(report);
  const post::PreviewScene scene = post::preview_scene(parsed.program, a.arc_tolerance_mm);
  slicer::write_file_atomic(a.svg_layer[1], post::render_svg(scene, o));
}

// Pose CSVs and rotary G-code: checked on their cylinder.
int run_curved_check(const CheckArgs& a, const std::string& text,
                     const machines::MachineProfile* machine, PhaseProgress* progress) {
  if (!a.svg_layer.empty())
    throw InputError("svg-layer: only for flat G-code (a curved file has no top view of a layer)");
  post::PoseCheckReport report;
  const auto mesh = is_csv(a.file) ? post::find_csv_mesh(a.file, a.substrate_mesh) : std::nullopt;
  if (mesh) {  // on a robot-held mesh: the cell from --machine, else the one it was planned for
    std::unique_ptr<machines::MachineProfile> planned;
    if (!machine && mesh->record)
      planned = std::make_unique<machines::MachineProfile>(machines::load_profile(mesh->record->machine));
    if (!machine && !planned)
      throw InputError(
          "machine: checking a pose CSV needs --machine (the robot cell, e.g. "
          "kuka-iiwa14-wasp-cylinder)");
    slicer::progress_phase(progress, "checking poses on the mesh");
    report = post::check_mesh_pose_csv(text, a.file, machine ? *machine : *planned, *mesh);
  } else if (is_csv(a.file)) {
    if (!machine)
      throw InputError(
          "machine: checking a pose CSV needs --machine (the robot cell, e.g. "
          "kuka-iiwa14-wasp-cylinder)");
    slicer::progress_phase(progress, "checking poses");
    report = post::check_pose_csv(text, a.file, *machine);
  } else {
    slicer::progress_phase(progress, "checking");
    report = post::check_rotary_gcode(text, a.file, machine);
  }
  if (progress) progress->finish();
  // Text from the file (feature names, notes) may be any bytes: dump_json keeps it valid UTF-8.
  std::cout << (a.json ? slicer::dump_json(post::to_json(report)) + "\n" : post::to_text(report));
  return report.ok() ? 0 : 1;
}

// --svg-layer draws from the whole parsed program: the file is read whole, as before.
post::CheckReport check_whole(const CheckArgs& a, const post::CheckOptions& options,
                              PhaseProgress* progress) {
  slicer::progress_phase(progress, "parsing");
  const std::string text = slicer::read_file(a.file);
  post::CheckInput in;
  try {
    in = post::read_for_check(text, options.machine, options.rules);
  } catch (const InputError& e) {
    throw InputError("input = " + a.file + ": " + e.what());
  }
  const post::ParsedGcode& parsed = in.parsed;
  if (parsed.program.moves.empty() && parsed.issues.empty())
    throw InputError("input = " + a.file + ": no moves to check (is it G-code?)");
  post::CheckOptions with_rules = options;
  with_rules.rules = in.rules;
  slicer::progress_phase(progress,
                         "checking " + std::to_string(parsed.program.layers.size()) + " layers");
  const post::CheckReport report = post::check_parsed(parsed, with_rules);
  slicer::progress_phase(progress, "drawing the layer");
  write_svg(parsed, report, a);
  return report;
}

// The file read and checked a layer at a time: memory flat in its size.
post::CheckReport check_streamed(const CheckArgs& a, const post::GcodeFile& file,
                                 const post::GcodeScan& scan, const post::CheckOptions& options,
                                 PhaseProgress* progress) {
  slicer::progress_phase(progress, "checking layers (MiB read)",
                         static_cast<std::size_t>(file.size_bytes() >> 20));
  post::CheckReport report;
  try {
    report = post::check_gcode_file(file, scan, options, progress);
  } catch (const InputError& e) {
    const std::string what = e.what();  // a read error names the file already
    throw InputError(what.starts_with("input = ") ? what : "input = " + a.file + ": " + what);
  }
  if (report.moves == 0 && report.parse_issues.empty())
    throw InputError("input = " + a.file + ": no moves to check (is it G-code?)");
  // The layer count is known at the end only: the file's layers, with deposits or without.
  const auto layers = std::count_if(report.layers.begin(), report.layers.end(),
                                    [](const post::LayerCheck& l) { return l.layer >= 0; });
  slicer::progress_phase(progress, "checked " +
                                       std::to_string(static_cast<std::size_t>(layers) +
                                                      report.layers_without_deposit) +
                                       " layers");
  return report;
}

int run_check(const CheckArgs& a) {
  if (!(a.arc_tolerance_mm >= post::kMinFlattenToleranceMm && a.arc_tolerance_mm <= 1.0)) {
    throw InputError("arc-tolerance = " + slicer::short_number(a.arc_tolerance_mm) +
                     ": must be in [0.001, 1] (mm)");
  }
  if (!a.substrate_mesh.empty() && !is_csv(a.file))
    throw InputError("substrate-mesh: only for a robot cell's pose CSV (" + a.file + " is not one)");
  const auto progress = command_progress("check", a.svg_layer.empty() ? 3 : 4);
  slicer::progress_phase(progress.get(), "reading");
  const post::GcodeFile file(a.file);
  const post::GcodeScan scan = is_csv(a.file) ? post::GcodeScan{} : file.scan();
  // A set whose writing was killed between two renames still has its journal: its files may
  // be half old and half new (a KRL .src that does not match its .dat).
  if (std::filesystem::exists(a.file + ".strand-commit")) {
    std::cout << "check: " << a.file
              << " belongs to an output set whose writing was interrupted (its journal "
              << a.file << ".strand-commit is still there): run the job again to complete it\n";
    return 1;
  }
  std::unique_ptr<machines::MachineProfile> machine;
  if (!a.machine.empty())
    machine = std::make_unique<machines::MachineProfile>(machines::load_profile(a.machine));
  if (is_csv(a.file) || scan.rotary)  // curved files are checked whole
    return run_curved_check(a, file.text(), machine.get(), progress.get());
  if (machine && machine->robot.enabled) {
    throw InputError(
        "machine = " + a.machine +
        ": a robot cell's motion is in its pose CSV; check that (strand check PART.csv --machine " +
        a.machine + ")");
  }
  post::CheckOptions options;
  if (!a.rules.empty()) {
    const std::string rules = slicer::match_choice(a.rules, {"diw", "fdm", "plot"}).value_or(a.rules);
    options.rules = post::RulesChoice{post::check_rules_from_string(rules), "given with --rules"};
  }
  options.arc_tolerance_mm = a.arc_tolerance_mm;
  options.touch_mm = slicer::kGcodeResolutionMm;
  options.machine = machine.get();
  const post::CheckReport report = a.svg_layer.empty()
                                       ? check_streamed(a, file, scan, options, progress.get())
                                       : check_whole(a, options, progress.get());
  if (progress) progress->finish();
  std::cout << (a.json ? slicer::dump_json(post::to_json(report)) + "\n" : post::to_text(report));
  return report.ok() ? 0 : 1;
}

}  // namespace

void add_check_command(CLI::App& app, Action& action) {
  CLI::App* sub = app.add_subcommand(
      "check", "check any G-code: strands, self-crossings, touches, arcs, bounds per layer");
  auto a = std::make_shared<CheckArgs>();
  sub->add_option("file", a->file, "G-code file, or a robot cell's pose CSV, to check")->required();
  sub->add_option("--machine", a->machine,
                  "machine profile name or .json path: also check build volume and arcs");
  sub->add_option("--rules", a->rules,
                  "diw: no crossing; fdm: infill may cross; plot: strokes may cross, pen read "
                  "from the file (default: plot for plotter profiles, fdm for files from an FDM "
                  "slicer, else diw)")
      ->type_name("diw|fdm|plot");
  sub->add_flag("--json", a->json, "print the report as JSON");
  sub->add_option("--svg-layer", a->svg_layer, "write a top view of layer N (0-based) to OUT.svg")
      ->expected(2)
      ->type_name("N OUT.svg");
  add_quantity_option(sub, "--arc-tolerance", a->arc_tolerance_mm, "mm",
                  "chord error when arcs are flattened for the search [mm] (default 0.01)");
  sub->add_option("--substrate-mesh", a->substrate_mesh,
                  "a pose CSV's substrate mesh (default: the one its record part.substrate.json "
                  "beside it names)");
  sub->callback([&action, a] { action = [a] { return run_check(*a); }; });
}

}  // namespace strand::cli
