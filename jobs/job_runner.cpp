// Job parsing and the generate-plan-emit-write chain, shared by every command that runs jobs.
#include "jobs/job_runner.h"

#include <stdexcept>

#include "jobs/curved_job.h"
#include "jobs/ink_profile.h"
#include "machines/gcode_format.h"
#include "machines/profile.h"
#include "postprocess/inspect/check.h"
#include "postprocess/inspect/crossings.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"
#include "slicer/json_input.h"
#include "slicer/params.h"

namespace strand::jobs {

namespace {

const char* const kJobKeys[] = {"generator", "machine", "params", "output", "report",
                                "arc-tolerance", "viewer-e", "substrate", "description", "schedule", "material", "tools"};

bool is_job_key(const std::string& k) {
  for (const char* known : kJobKeys) {
    if (k == known) return true;
  }
  return false;
}

std::string generator_names() {
  std::string names;
  for (const auto& g : patterns::generators()) names += (names.empty() ? "" : ", ") + g.name;
  return names;
}

// Chords coarser than the default can cut into a neighbouring pass (a chord lies inside its
// arc by up to the tolerance): the planned program is searched for crossings and refused.
void refuse_crossing_chords(const slicer::MotionProgram& program, const JobSettings& s) {
  const post::ContactReport contacts =
      post::find_contacts(program, slicer::kDefaultArcToleranceMm, slicer::kGcodeResolutionMm);
  if (contacts.crossings.empty()) return;
  const slicer::Vec2 at = contacts.crossings.front().at_mm;
  throw InputError("arc-tolerance = " + slicer::short_number(s.arc_tolerance_mm) + ": the chords cross the strand at " +
                   std::to_string(contacts.crossings.size()) + " place(s), first near (" +
                   machines::fmt_xyz(at.x()) + ", " + machines::fmt_xyz(at.y()) +
                   ") mm; use a smaller tolerance (the default " +
                   slicer::short_number(slicer::kDefaultArcToleranceMm) + " mm keeps every pass apart)");
}

// Debug builds: every file a generator writes must pass `strand check` on its machine.
[[maybe_unused]] void assert_passes_check(const std::string& gcode, const machines::MachineProfile& m) {
  post::CheckOptions o;
  o.machine = &m;
  o.touch_mm = slicer::kGcodeResolutionMm;
  const post::CheckReport report = post::check_gcode(gcode, o);
  if (!report.ok()) throw std::logic_error("generated G-code fails strand check:\n" + post::to_text(report));
}

}  // namespace

void vet_produced(const post::Produced& produced, const machines::MachineProfile& machine,
                  double arc_tolerance_mm) {
  // Never an empty print (issue 29): a job that deposits nothing is refused before its file
  // is kept (a streamed body stays in the output transaction's temp file, which is dropped).
  const nlohmann::json totals = produced.report.value("totals", nlohmann::json::object());
  if (totals.value("deposit_length_mm", 0.0) <= 0.0) {
    throw InputError(produced.report.value("generator", std::string("job")) +
                     ": every layer is empty (" + std::to_string(totals.value("layers", 0)) +
                     " layers, nothing deposited)");
  }
  JobSettings s;
  s.arc_tolerance_mm = arc_tolerance_mm;
  if (s.arc_tolerance_mm > slicer::kDefaultArcToleranceMm) refuse_crossing_chords(produced.program, s);
#ifndef NDEBUG
  assert_passes_check(produced.gcode, machine);
#else
  (void)machine;
#endif
}

JobSpec job_spec_from_json(const nlohmann::json& j, const std::string& where) {
  if (!j.is_object()) throw InputError(where + ": must be a JSON object");
  std::vector<std::string> problems;
  for (const auto& [k, v] : j.items()) {
    if (!is_job_key(k)) {
      problems.push_back(where + "." + k +
                         ": unknown key (generator, machine, params, output, report, "
                         "arc-tolerance, viewer-e, substrate, description, schedule, material, tools)");
    }
  }
  if (!problems.empty()) throw InputError(problems);
  JobSpec s;
  const std::string name = slicer::get_text(j, "generator", where, "");
  s.generator = patterns::find_generator(name);
  if (!s.generator) {
    throw InputError(where + ".generator = " + name + ": must be one of " + generator_names());
  }
  s.settings.machine = slicer::get_text(j, "machine", where, s.settings.machine);
  s.settings.output = slicer::get_text(j, "output", where, "");
  s.settings.report = slicer::get_text(j, "report", where, "");
  s.settings.arc_tolerance_mm =
      slicer::get_number(j, "arc-tolerance", where, s.settings.arc_tolerance_mm);
  s.settings.viewer_e = slicer::get_bool(j, "viewer-e", where, false);
  s.params = j.value("params", nlohmann::json::object());
  if (!s.params.is_object()) {
    throw InputError(where + ".params: must be an object of parameter values, e.g. {\"nozzle\": 0.84}");
  }
  if (j.contains("substrate") && !j.at("substrate").is_object()) {
    throw InputError(where + ".substrate: must be an object like {\"type\": \"cylinder\", \"radius\": 20, "
                     "\"length\": 100}");
  }
  s.settings.substrate = j.value("substrate", nlohmann::json::object());
  s.description = slicer::get_text(j, "description", where, "");
  if (j.contains("schedule")) {
    if (s.generator->name != "scaffold") {
      throw InputError(where + ".schedule: only the scaffold generator takes a schedule (not " + name + ")");
    }
    if (!s.settings.substrate.empty()) {
      throw InputError(where + ".schedule: a scheduled scaffold is flat (no substrate)");
    }
    s.settings.schedule = j.at("schedule");
  }
  if (j.contains("tools")) {
    post::tool_assignment_from_json(j.at("tools"), where + ".tools");  // checked here, applied when planned
    s.settings.tools = j.at("tools");
  }
  // An ink profile (strand calibrate) sets speed and layer height unless params give them.
  if (j.contains("material")) {
    const std::string material = slicer::get_text(j, "material", where, "");
    s.settings.material = apply_ink_profile(load_ink_profile(material), material, s.generator->table(), s.params);
  }
  return s;
}

post::ToolAssignment tools_for(const nlohmann::json& tools, const machines::MachineProfile& machine,
                               const std::string& what) {
  post::ToolAssignment a = post::tool_assignment_from_json(tools, what);
  const int count = machines::tool_count(machine);
  if (a.highest() >= count) {
    throw InputError(what + " = " + (tools.is_string() ? tools.get<std::string>() : tools.dump()).substr(0, 80) + ": tool " +
                     std::to_string(a.highest()) + " is not on machine " + machine.name + " (" + std::to_string(count) +
                     " tool(s): 0 to " + std::to_string(count - 1) + ")");
  }
  return a;
}

namespace {

struct Prepared {
  std::unique_ptr<slicer::LayerSource> layers;
  machines::MachineProfile machine;
  post::PlanOptions options;
};

// Everything a job checks before planning: arc tolerance, machine, parameters.
Prepared prepare(const patterns::GeneratorSpec& generator, const nlohmann::json& params,
                 const JobSettings& s) {
  if (!(s.arc_tolerance_mm > 0.0 && s.arc_tolerance_mm <= 1.0)) {
    throw InputError("arc-tolerance = " + slicer::short_number(s.arc_tolerance_mm) +
                     ": must be in (0, 1] (mm)");
  }
  if (!s.substrate.empty()) {
    throw InputError(
        "substrate: a job on a curved substrate writes robot programs or 4-axis G-code; run it "
        "with strand job or strand " +
        generator.name + ", not in a sweep");
  }
  Prepared p;
  p.machine = machines::load_profile(s.machine);
  if (p.machine.plotter.enabled) {
    throw InputError("machine = " + s.machine + ": a pen plotter; " + generator.name +
                     " needs a printer profile (strand machines lists them)");
  }
  if (p.machine.robot.enabled || p.machine.rotary.enabled) {
    throw InputError("machine = " + s.machine + " (" + machines::to_string(p.machine.volume.kind) +
                     "): prints on a cylinder; give --substrate cylinder --substrate-radius MM "
                     "--substrate-length MM");
  }
  nlohmann::json values = slicer::resolve_params(generator.table(), params);
  if (!s.schedule.is_null()) values["schedule"] = s.schedule;
  slicer::progress_phase(s.progress, "generating");
  p.layers = generator.layers(values);
  p.options = post::plan_options_from(p.layers->record, s.arc_tolerance_mm);
  if (s.material.is_object() && s.material.contains("flow") && s.material.at("flow").is_number()) {
    p.options.flow = s.material.at("flow").get<double>();
  }
  if (!s.tools.is_null()) {
    p.options.tools = tools_for(s.tools, p.machine, "tools");
  }
  return p;
}

// The layers are planned and written one at a time (memory independent of the job's size);
// the whole program is kept only where a check needs it (chords coarser than the default).
post::Produced produce_prepared(Prepared& p, const patterns::GeneratorSpec& generator,
                                const JobSettings& s, const post::GcodeStreams& streams) {
  post::ProduceOptions po;
  po.gcode_path = job_output_path(generator, s);
  po.viewer_e = s.viewer_e;
  po.streams = streams;
  po.progress = s.progress;
  po.keep_program = s.keep_program || s.arc_tolerance_mm > slicer::kDefaultArcToleranceMm;
  post::Produced produced = post::produce_layers(*p.layers, p.machine, p.options, po);
  slicer::progress_phase(s.progress, "checking");
  vet_produced(produced, p.machine, s.arc_tolerance_mm);
  if (!s.material.is_null()) produced.report["material"] = s.material;
  if (!s.tools.is_null()) produced.report["tools"] = s.tools;
  return produced;
}

}  // namespace

post::Produced produce_job(const patterns::GeneratorSpec& generator, const nlohmann::json& params,
                           const JobSettings& s) {
  Prepared p = prepare(generator, params, s);
  return produce_prepared(p, generator, s, {});
}

std::string viewer_output_path(const std::string& out) {
  const auto dot = out.rfind('.');
  const auto slash = out.find_last_of("/\\");
  const bool has_ext = dot != std::string::npos && (slash == std::string::npos || dot > slash);
  return (has_ext ? out.substr(0, dot) : out) + ".viewer-e.gcode";
}

std::string in_job_folder(const std::string& path, const JobSettings& s) {
  return s.folder.empty() || (!path.empty() && path.front() == '/') ? path : s.folder + "/" + path;
}

std::string job_output_path(const patterns::GeneratorSpec& generator, const JobSettings& s) {
  if (!s.output.empty()) return s.output;
  return (s.output_stem.empty() ? generator.name : s.output_stem) + ".gcode";
}

post::Produced run_job(const patterns::GeneratorSpec& generator, const nlohmann::json& params,
                       const JobSettings& s) {
  if (!s.substrate.empty()) return run_curved_job(generator, params, s);
  slicer::OutputFiles out;
  for (const std::string& input : s.inputs) out.protect_input(input);
  const std::string path = in_job_folder(job_output_path(generator, s), s);  // the report names it as given
#ifndef NDEBUG
  // Debug builds check the whole text of every file they write (produce_job).
  post::Produced produced = produce_job(generator, params, s);
  out.stage(path, produced.gcode);
  if (s.viewer_e) out.stage(viewer_output_path(path), produced.viewer_gcode);
#else
  // Layer by layer: the G-code body streams into its temp file as it is formatted and the
  // head (which holds the totals) goes before it at commit, so a large job never holds its
  // toolpath, program or text.
  Prepared p = prepare(generator, params, s);
  std::ostream& gcode = out.stage_stream(path);
  std::ostream* viewer = s.viewer_e ? &out.stage_stream(viewer_output_path(path)) : nullptr;
  post::Produced produced = produce_prepared(p, generator, s, {&gcode, viewer});  // chords only
  out.prepend(path, produced.gcode_head);
  if (s.viewer_e) out.prepend(viewer_output_path(path), produced.viewer_gcode_head);
#endif
  if (!s.report.empty()) out.stage(in_job_folder(s.report, s), slicer::dump_json(produced.report) + "\n");
  slicer::progress_phase(s.progress, "writing files");
  out.commit();
  return produced;
}

}  // namespace strand::jobs
