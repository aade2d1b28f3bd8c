// `strand <generator>`: flags from the generator's parameter table, then generate, plan,
// emit, write atomically, report.
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>

#include "machines/profile.h"
#include "patterns/registry.h"
#include "cli/commands.h"
#include "jobs/ink_profile.h"
#include "jobs/job_runner.h"
#include "cli/param_flags.h"
#include "cli/progress_bar.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"
#include "slicer/json_input.h"
#include "slicer/params.h"
#include "slicer/substrate_params.h"
#include "slicer/tolerances.h"

namespace strand::cli {

using jobs::JobSettings;
using jobs::JobSpec;
using jobs::apply_ink_profile;
using jobs::job_output_path;
using jobs::job_spec_from_json;
using jobs::load_ink_profile;
using jobs::run_job;
using jobs::viewer_output_path;

namespace {

struct GenerateArgs {
  ParamFlags flags;
  ParamFlags substrate;  // keys of slicer::substrate_table(), flags --substrate-radius etc.
  std::string machine = "deltawasp-2040-clay";
  std::string output;
  std::string report;
  double arc_tolerance_mm = slicer::kDefaultArcToleranceMm;
  bool viewer_e = false;
  std::string material;  // ink profile name or .json path (jobs/ink_profile.h)
  std::string tools;     // printheads by feature or layer (postprocess/plan/tool_assignment.h)
};

// The shared tail of `strand <generator>` and `strand job`: nothing is written unless
// every step succeeded.
int run_and_print(const patterns::GeneratorSpec& spec, const nlohmann::json& given,
                  JobSettings s) {
  const auto progress = command_progress(spec.name, s.substrate.empty() ? 4 : 3);
  s.progress = progress.get();
  const std::string summary = run_job(spec, given, s).summary;
  if (progress) progress->finish();
  std::cout << summary;
  if (s.viewer_e) {
    std::cout << "  preview copy   " << viewer_output_path(job_output_path(spec, s))
              << " (computed E, not for printing)\n";
  }
  return 0;
}

int run_generator(const patterns::GeneratorSpec& spec, const GenerateArgs& a) {
  const auto& table = spec.table();
  JobSettings settings{a.machine, a.output, a.report, a.arc_tolerance_mm, a.viewer_e};
  settings.substrate = given_params(slicer::substrate_table(), a.substrate);
  nlohmann::json given = given_params(table, a.flags);
  if (!a.material.empty()) settings.material = apply_ink_profile(load_ink_profile(a.material), a.material, table, given);
  if (!a.tools.empty()) settings.tools = a.tools;
  return run_and_print(spec, given, settings);
}

// The curved-substrate flags of every generator, named as the table says (--substrate,
// --substrate-radius, --substrate-length, --wrap, --arc-length-at).
void add_substrate_flags(CLI::App* sub, ParamFlags& flags) {
  for (const auto& d : slicer::substrate_table().defs) {
    flags.options[d.key] = sub->add_option("--" + slicer::substrate_flag(d.key), flags.text[d.key], help_for(d))
                               ->type_name(type_name_for(d))
                               ->group("Curved substrate");
  }
}

// Job file: {"generator", "machine", "params": {flag: value}, "output", "report",
// "arc-tolerance"}; relative output paths are relative to the current directory.
nlohmann::json read_job(const std::string& path) {
  return slicer::parse_json(slicer::read_file(path), "job = " + path);
}

int run_job_json(const nlohmann::json& j, const std::string& path) {
  if (!j.is_object()) throw InputError("job = " + path + ": must be a JSON object");
  JobSpec job = job_spec_from_json(j, "job");
  // A substrate mesh named in a job file is found from the job file's folder (it travels
  // with the job, as samples/meshes/ does with samples/).
  auto& substrate = job.settings.substrate;
  if (substrate.is_object() && substrate.contains("mesh") && substrate.at("mesh").is_string()) {
    const std::filesystem::path mesh(substrate.at("mesh").get<std::string>());
    if (mesh.is_relative())
      substrate["mesh"] = (std::filesystem::path(path).parent_path() / mesh).lexically_normal().string();
  }
  job.settings.inputs.push_back(path);
  job.settings.output_stem = std::filesystem::path(path).stem().string();  // spec.json -> spec.gcode
  return run_and_print(*job.generator, job.params, job.settings);
}

}  // namespace

void add_generator_commands(CLI::App& app, Action& action) {
  for (const auto& spec : patterns::generators()) {
    auto args = std::make_shared<GenerateArgs>();
    CLI::App* sub = app.add_subcommand(spec.name, spec.summary);
    add_param_flags(sub, spec.table(), args->flags);
    add_substrate_flags(sub, args->substrate);
    sub->add_option("--machine", args->machine, "machine profile name or path to a .json profile (default deltawasp-2040-clay)");
    sub->add_option("-o,--output", args->output,
                    "G-code file to write (default " + spec.name +
                        ".gcode; a robot cell writes <name>.csv with <Class>.java, <module>.src/.dat, .extruder.gcode)");
    sub->add_option("--report", args->report, "write a JSON report here");
    sub->add_option("--material", args->material,
                    "ink profile (materials/NAME.json from strand calibrate): its speed and layer height "
                    "unless given");
    sub->add_option("--tools", args->tools,
                    "printheads of a multi-tool machine: by feature (node=1,ligament=0) or cycled per layer "
                    "(layers=0,1)");
    add_quantity_option(sub, "--arc-tolerance", args->arc_tolerance_mm, "mm",
                    "max chord error when arcs become G1 segments [mm] (default 0.01)");
    sub->add_flag("--viewer-e", args->viewer_e,
                  "also write <output>.viewer-e.gcode: computed E for viewers, not for printing");
    const patterns::GeneratorSpec* s = &spec;
    sub->callback([&action, s, args] { action = [s, args] { return run_generator(*s, *args); }; });
  }
}

void add_job_command(CLI::App& app, Action& action) {
  CLI::App* sub = app.add_subcommand("job", "run a generator from a JSON job file");
  auto path = std::make_shared<std::string>();
  auto output = std::make_shared<std::string>();
  auto report = std::make_shared<std::string>();
  sub->add_option("spec", *path, "job file (JSON)")->required();
  sub->add_option("-o,--output", *output,
                  "override the job's output path (default: the job's \"output\", else SPEC's name "
                  "with .gcode, or .csv for a robot cell)");
  sub->add_option("--report", *report, "override the job's report path");
  sub->callback([&action, path, output, report] {
    action = [path, output, report] {
      nlohmann::json j = read_job(*path);
      if (j.is_object() && !output->empty()) j["output"] = *output;
      if (j.is_object() && !report->empty()) j["report"] = *report;
      return run_job_json(j, *path);
    };
  });
}

void add_machines_command(CLI::App& app, Action& action) {
  CLI::App* sub = app.add_subcommand(
      "machines", "list the machine profiles (shipped and your own), show or check one");
  auto json = std::make_shared<bool>(false);
  sub->add_flag("--json", *json, "the list as JSON (name, description, origin)");
  sub->require_subcommand(0, 1);
  sub->callback([sub, &action, json] {
    if (!sub->get_subcommands().empty()) return;  // show / check set the action
    action = [json] {
      const auto catalog = machines::profile_catalog();
      if (*json) {
        nlohmann::json list = nlohmann::json::array();
        for (const auto& p : catalog) {
          list.push_back({{"name", p.name},
                          {"description", p.description},
                          {"origin", p.origin},
                          {"shadows_shipped", p.shadows_shipped}});
        }
        std::cout << list.dump(2) << "\n";
        return 0;
      }
      for (const auto& p : catalog) {
        std::cout << p.name << "  " << p.description;
        if (p.origin != "shipped") {
          std::cout << "  [" << p.origin << (p.shadows_shipped ? ", shadows the shipped one" : "")
                    << "]";
        }
        std::cout << "\n";
      }
      return 0;
    };
  });

  CLI::App* show = sub->add_subcommand("show", "print a profile's JSON (to copy and edit)");
  auto name = std::make_shared<std::string>();
  show->add_option("name", *name, "profile name")->required();
  show->callback([&action, name] {
    action = [name] {
      for (const auto& p : machines::profile_catalog()) {
        if (p.name == *name) {
          std::cout << p.json_text << (p.json_text.ends_with("\n") ? "" : "\n");
          return 0;
        }
      }
      machines::load_profile(*name);  // the unknown-machine message with the names
      return 2;
    };
  });

  CLI::App* check =
      sub->add_subcommand("check", "validate a profile file: every problem, one per line");
  auto file = std::make_shared<std::string>();
  check->add_option("file", *file, "profile (.json)")->required();
  check->callback([&action, file] {
    action = [file] {
      const std::string text = slicer::read_file(*file);
      const auto j = slicer::parse_json(text, "machines.check = " + *file);
      const std::string origin = "machine " + *file;
      try {
        const auto profile = machines::profile_from_json(j, origin);
        std::cout << *file << ": ok (" << machines::to_string(profile.volume.kind) << ", "
                  << machines::to_string(profile.firmware) << ")\n";
        return 0;
      } catch (const InputError& e) {
        // Each problem starts with the origin; the joined message is split back at them.
        const std::string all = e.what(), separator = "; " + origin + ":";
        std::size_t start = 0;
        while (true) {
          const auto next = all.find(separator, start);
          std::cerr << all.substr(start, next - start) << "\n";
          if (next == std::string::npos) break;
          start = next + 2;
        }
        return 2;
      }
    };
  });
}

}  // namespace strand::cli
