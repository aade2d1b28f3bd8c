// Job parsing and the generate-plan-emit-write chain, shared by every command that runs jobs.
#include "cli/job_runner.h"

#include <optional>

#include "machines/profile.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"
#include "slicer/params.h"

namespace strand::cli {

namespace {

const char* const kJobKeys[] = {"generator", "machine", "params", "output",
                                "report", "arc-tolerance", "viewer-e", "description"};

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
                         ": unknown key (generator, machine, params, output, report, arc-tolerance, viewer-e, description)");
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
  s.description = j.value("description", std::string());
  return s;
}

namespace {

struct Prepared {
  slicer::Toolpath toolpath;
  machines::MachineProfile machine;
  post::PlanOptions options;
};

// Everything a job checks before planning: arc tolerance, parameters, machine.
Prepared prepare(const patterns::GeneratorSpec& generator, const nlohmann::json& params,
                 const JobSettings& s) {
  if (!(s.arc_tolerance_mm > 0.0 && s.arc_tolerance_mm <= 1.0)) {
    throw InputError("arc-tolerance = " + slicer::short_number(s.arc_tolerance_mm) +
                     ": must be in (0, 1] (mm)");
  }
  const nlohmann::json values = slicer::resolve_params(generator.table(), params);
  Prepared p{generator.generate(values), {}, {}};
  p.machine = machines::load_profile(s.machine);
  p.options = post::plan_options_from(p.toolpath, s.arc_tolerance_mm);
  return p;
}

}  // namespace

post::Produced produce_job(const patterns::GeneratorSpec& generator, const nlohmann::json& params,
                           const JobSettings& s) {
  Prepared p = prepare(generator, params, s);
  return post::produce(std::move(p.toolpath), p.machine, p.options, job_output_path(generator, s),
                       s.viewer_e);
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
  Prepared p = prepare(generator, params, s);
  // G-code streams into temp files as it is formatted; all are renamed at the end, and an
  // error midway (a part that does not fit) leaves no output at all.
  const std::string path = job_output_path(generator, s);
  slicer::AtomicFile gcode(path);
  std::optional<slicer::AtomicFile> viewer;
  if (s.viewer_e) viewer.emplace(viewer_output_path(path));
  std::optional<slicer::AtomicFile> report;
  if (!s.report.empty()) report.emplace(s.report);
  post::Produced produced = post::produce(std::move(p.toolpath), p.machine, p.options, path,
                                          s.viewer_e, {&gcode.out(), viewer ? &viewer->out() : nullptr});
  if (report) report->out() << produced.report.dump(2) << "\n";
  gcode.commit();
  if (viewer) viewer->commit();
  if (report) report->commit();
  return produced;
}

}  // namespace strand::cli
