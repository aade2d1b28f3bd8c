// Running one job (generator + parameters + machine) without printing: the shared core of
// `strand <generator>`, `strand job` and `strand sweep`.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "patterns/registry.h"
#include "postprocess/plan/produce.h"
#include "slicer/progress_listener.h"
#include "slicer/tolerances.h"

namespace strand::jobs {

struct JobSettings {
  std::string machine = "deltawasp-2040-clay";
  std::string output;  // empty: "<output_stem>.gcode"
  std::string report;  // empty: no report file
  double arc_tolerance_mm = slicer::kDefaultArcToleranceMm;
  bool viewer_e = false;  // also write the preview-only copy with computed E
  std::vector<std::string> inputs;  // files the outputs must never overwrite (the job file)
  // Curved substrate, keys of slicer::substrate_table() ("type", "radius", ...); empty = flat.
  nlohmann::json substrate = nlohmann::json::object();
  // Told each phase (generating, planning, writing G-code); not owned, null: nobody.
  slicer::Progress* progress = nullptr;
  // The default output's name without extension; empty: the generator's name (`strand job
  // spec.json` sets "spec").
  std::string output_stem;
  // produce_job also returns the whole planned program (Produced::program), for front ends
  // that show the moves (the Python module's NumPy arrays).
  bool keep_program = false;
  // --material: the ink profile's name, file, applied values and measurements, recorded in
  // the report (null: none).
  nlohmann::json material;
  // A job file's "schedule" (per-layer-range values; strand scaffold only), given to the
  // generator as the value "schedule" after the table's check; null: none.
  nlohmann::json schedule;
  // --tools / a job file's "tools": printheads by feature or layer (issue 33), as text
  // ("node=1,ligament=0", "layers=0,1") or {"by_feature": {...}} / {"by_layer": [...]};
  // null: every stroke on tool 0.
  nlohmann::json tools;
  // The job's folder: its relative output, viewer copy, report and substrate mesh are found
  // there, and its files name them as `strand job` run in that folder does (the workbench's
  // job folders, whose files must not name the server's directories); empty: the current
  // directory.
  std::string folder;
};

// A job file's content, checked: {"generator", "machine", "params", "output", "report",
// "arc-tolerance", "viewer-e", "substrate", "description", "schedule", "material", "tools"} ("material":
// an ink profile's name or .json path, applied as --material is).
struct JobSpec {
  const patterns::GeneratorSpec* generator = nullptr;
  nlohmann::json params = nlohmann::json::object();  // as given, keys = CLI long flags
  JobSettings settings;
  std::string description;
};

// --tools text or a job file's "tools" checked against the machine: InputError "WHAT = ...:
// tool N is not on machine M (K tool(s): 0 to K-1)" for a head it lacks.
post::ToolAssignment tools_for(const nlohmann::json& tools, const machines::MachineProfile& machine,
                               const std::string& what);

// Checks the keys and the generator name; `where` prefixes messages ("job", "sweep.job").
// Throws InputError naming the key path.
JobSpec job_spec_from_json(const nlohmann::json& j, const std::string& where);

// The checks every produced file passes before it is written: a file that deposits nothing
// and coarse chords that cross a neighbouring pass are refused (InputError); debug builds
// also assert `strand check`.
void vet_produced(const post::Produced& produced, const machines::MachineProfile& machine,
                  double arc_tolerance_mm);

// Generates, plans and emits a flat (planar) job in memory; nothing is written. Throws
// InputError for bad parameters, an unknown machine, a part that does not fit, or a job on a
// curved substrate (those run through run_job, see curved_job.h).
post::Produced produce_job(const patterns::GeneratorSpec& generator, const nlohmann::json& params,
                           const JobSettings& settings);

// The G-code path a job writes: settings.output, or "<output_stem or generator>.gcode".
std::string job_output_path(const patterns::GeneratorSpec& generator, const JobSettings& settings);

// `path` (an output, report or mesh of the job) as a path from the current directory: in
// settings.folder when it is relative.
std::string in_job_folder(const std::string& path, const JobSettings& settings);

// "out/x.gcode" -> "out/x.viewer-e.gcode": the preview-only copy beside the printable file.
std::string viewer_output_path(const std::string& gcode_path);

// produce_job, then writes the G-code, viewer copy and report as one transaction (all or
// none); in release builds the G-code streams into its temp file as it is formatted
// (Produced::gcode stays empty). Returns what was produced. A job with a substrate runs as a
// curved job (curved_job.h) and returns its report and summary.
post::Produced run_job(const patterns::GeneratorSpec& generator, const nlohmann::json& params,
                       const JobSettings& settings);

}  // namespace strand::jobs
