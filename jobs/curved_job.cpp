// Curved jobs from the CLI and job files: substrate, generation (flat or wrapped), outputs.
#include "jobs/curved_job.h"

#include "machines/profile.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"
#include "slicer/json_input.h"
#include "slicer/params.h"
#include "slicer/substrate_params.h"
#include "slicer/units.h"

namespace strand::jobs {

namespace {

// The pattern to lay on the cylinder. For --wrap full the design is made periodic with one
// circumference as its period, measured where the arc length is (the substrate, or the first
// layer's bead centre: half a layer height above it).
slicer::Toolpath pattern_for(const patterns::GeneratorSpec& g, const nlohmann::json& values,
                             const slicer::SubstrateSpec& s) {
  if (s.wrap == slicer::Wrap::Patch) return g.generate(values);
  if (g.generate_wrapped == nullptr) {
    throw InputError("substrate.wrap = full: not supported for " + g.name +
                     " (no periodic variant of this design yet; use --wrap patch)");
  }
  double lift = 0.0;
  if (s.arc_length_at == slicer::ArcLengthAt::Deposition) {
    const slicer::Toolpath flat = g.generate(values);
    if (!flat.layers.empty()) lift = flat.layers.front().height_mm / 2.0;
  }
  return g.generate_wrapped(values, slicer::kTwoPi * (s.radius_mm + lift));
}

std::string default_output(const patterns::GeneratorSpec& g, const machines::MachineProfile& m,
                           const JobSettings& s) {
  return (s.output_stem.empty() ? g.name : s.output_stem) + (m.robot.enabled ? ".csv" : ".gcode");
}

}  // namespace

post::CurvedProduced produce_curved_job(const patterns::GeneratorSpec& g,
                                        const nlohmann::json& params, const JobSettings& s) {
  if (!(s.arc_tolerance_mm > 0.0 && s.arc_tolerance_mm <= 1.0)) {
    throw InputError("arc-tolerance = " + slicer::short_number(s.arc_tolerance_mm) +
                     ": must be in (0, 1] (mm)");
  }
  if (s.viewer_e)
    throw InputError("viewer-e: only for flat G-code jobs (a curved job has no planar G-code)");
  auto substrate = slicer::substrate_from(s.substrate);
  if (substrate) substrate->mesh_folder = s.folder;
  const nlohmann::json values = slicer::resolve_params(g.table(), params);
  const machines::MachineProfile machine = machines::load_profile(s.machine);
  slicer::progress_phase(s.progress, "generating");
  const slicer::Toolpath t = pattern_for(g, values, *substrate);
  const std::string output = s.output.empty() ? default_output(g, machine, s) : s.output;
  slicer::progress_phase(s.progress, "planning and writing");
  return post::produce_curved(t, *substrate, machine, s.arc_tolerance_mm, output);
}

post::Produced run_curved_job(const patterns::GeneratorSpec& g, const nlohmann::json& params,
                              const JobSettings& s) {
  post::CurvedProduced c = produce_curved_job(g, params, s);
  slicer::OutputFiles files;
  for (const std::string& input : s.inputs) files.protect_input(input);
  for (const auto& [path, content] : c.files) files.stage(in_job_folder(path, s), content);
  if (!s.report.empty()) files.stage(in_job_folder(s.report, s), slicer::dump_json(c.report) + "\n");
  slicer::progress_phase(s.progress, "writing files");
  files.commit();
  post::Produced out;
  out.report = std::move(c.report);
  out.summary = std::move(c.summary);
  return out;
}

}  // namespace strand::jobs
