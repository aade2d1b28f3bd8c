// Job parsing and the generate-plan-emit-write chain, shared by every command that runs jobs.
#include "cli/job_runner.h"

#include "cli/curved_job.h"
#include "machines/profile.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"
#include "slicer/params.h"

namespace strand::cli {

namespace {

const char* const kJobKeys[] = {"generator", "machine", "params", "output", "report",
                                "arc-tolerance", "viewer-e", "substrate", "description"};

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

}  // namespace

JobSpec job_spec_from_json(const nlohmann::json& j, const std::string& where) {
  if (!j.is_object()) throw InputError(where + ": must be a JSON object");
  std::vector<std::string> problems;
  for (const auto& [k, v] : j.items()) {
    if (!is_job_key(k)) {
      problems.push_back(where + "." + k +
                         ": unknown key (generator, machine, params, output, report, "
                         "arc-tolerance, viewer-e, substrate, description)");
    }
  }
  if (!problems.empty()) throw InputError(problems);
  JobSpec s;
  const std::string name = j.value("generator", std::string());
  s.generator = patterns::find_generator(name);
  if (!s.generator) {
    throw InputError(where + ".generator = " + name + ": must be one of " + generator_names());
  }
  s.settings.machine = j.value("machine", s.settings.machine);
  s.settings.output = j.value("output", std::string());
  s.settings.report = j.value("report", std::string());
  s.settings.arc_tolerance_mm = j.value("arc-tolerance", s.settings.arc_tolerance_mm);
  if (j.contains("viewer-e") && !j.at("viewer-e").is_boolean()) {
    throw InputError(where + ".viewer-e = " + j.at("viewer-e").dump() + ": must be true or false");
  }
  s.settings.viewer_e = j.value("viewer-e", false);
  s.params = j.value("params", nlohmann::json::object());
  if (j.contains("substrate") && !j.at("substrate").is_object()) {
    throw InputError(
        where + ".substrate = " + j.at("substrate").dump() +
        ": must be an object like {\"type\": \"cylinder\", \"radius\": 20, \"length\": 100}");
  }
  s.settings.substrate = j.value("substrate", nlohmann::json::object());
  s.description = j.value("description", std::string());
  return s;
}

post::Produced produce_job(const patterns::GeneratorSpec& generator, const nlohmann::json& params,
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
  const nlohmann::json values = slicer::resolve_params(generator.table(), params);
  const machines::MachineProfile machine = machines::load_profile(s.machine);
  if (machine.robot.enabled || machine.rotary.enabled) {
    throw InputError("machine = " + s.machine + " (" + machines::to_string(machine.volume.kind) +
                     "): prints on a cylinder; give --substrate cylinder --substrate-radius MM "
                     "--substrate-length MM");
  }
  const slicer::Toolpath t = generator.generate(values);
  return post::produce(t, machine, post::plan_options_from(t, s.arc_tolerance_mm),
                       job_output_path(generator, s), s.viewer_e);
}

std::string viewer_output_path(const std::string& out) {
  const auto dot = out.rfind('.');
  const auto slash = out.find_last_of("/\\");
  const bool has_ext = dot != std::string::npos && (slash == std::string::npos || dot > slash);
  return (has_ext ? out.substr(0, dot) : out) + ".viewer-e.gcode";
}

std::string job_output_path(const patterns::GeneratorSpec& generator, const JobSettings& s) {
  return s.output.empty() ? generator.name + ".gcode" : s.output;
}

post::Produced run_job(const patterns::GeneratorSpec& generator, const nlohmann::json& params,
                       const JobSettings& s) {
  if (!s.substrate.empty()) return run_curved_job(generator, params, s);
  post::Produced produced = produce_job(generator, params, s);
  const std::string report = produced.report.dump(2) + "\n";
  slicer::write_file_atomic(job_output_path(generator, s), produced.gcode);
  if (s.viewer_e) {
    slicer::write_file_atomic(viewer_output_path(job_output_path(generator, s)), produced.viewer_gcode);
  }
  if (!s.report.empty()) slicer::write_file_atomic(s.report, report);
  return produced;
}

}  // namespace strand::cli
