// Running a sweep: every point of this shard in parallel (TBB), each G-code and preview
// written atomically, failures recorded per point, up-to-date points reused.
#pragma once

#include <cstddef>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "postprocess/preview/preview_scene.h"
#include "jobs/sweep_spec.h"

namespace strand::jobs {

struct SweepOptions {
  std::string dir;        // output directory (created if missing)
  int jobs = 0;           // worker threads; 0 = every core
  Shard shard;            // 1/1 = the whole sweep
  bool previews = true;   // a PNG thumbnail and an HTML viewer per point in DIR/previews/
};

struct SweepProgress {
  std::size_t done = 0, total = 0, failed = 0, reused = 0;
  const nlohmann::json* row = nullptr;  // the point just finished
};
// Called once per finished point, never concurrently.
using ProgressFn = std::function<void(const SweepProgress&)>;

struct SweepResult {
  nlohmann::json manifest;  // what manifest.json (or the shard's manifest) holds
  std::size_t ran = 0, reused = 0, failed = 0, dropped = 0;
};

// A point is up to date, and is not run again, when the manifest already in `dir` lists it
// as ok with the same parameters hash (generator, machine name or profile file content,
// arc tolerance, parameters and Strand version) and its G-code is present with the
// recorded content hash.
// Each finished point is also appended to the shard's journal (jobs/sweep_journal.h), read
// like the manifest on the next run and removed once the manifest is written, so a sweep
// interrupted before its manifest resumes where it stopped.
// Writes the G-codes, previews, the manifest(s) and, for an unsharded run, index.html.
// Throws InputError only for problems of the whole sweep (unwritable directory).
SweepResult run_sweep(const SweepSpec& spec, const nlohmann::json& source, const SweepOptions& options,
                      const ProgressFn& progress);

// The thumbnail drawn for each point: top view of every layer, coloured by feature.
std::string thumbnail_png(const post::PreviewScene& scene);

}  // namespace strand::jobs
