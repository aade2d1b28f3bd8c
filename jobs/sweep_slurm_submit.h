// Submitting a sweep to Slurm: the scripts written, sbatch run (no shell between: every
// path and option is one argv word), the array and merge job ids recorded in
// DIR/slurm/sweep.json, and --resume's choice of the shards left to run.
#pragma once

#include <string>
#include <vector>

#include "jobs/sweep_slurm.h"

namespace strand::jobs {

struct ProcessResult {
  int exit_code = -1;  // 128 + signal when killed; 127 when the program cannot be started
  std::string out, err;
};
// Runs argv (argv[0] looked up on PATH) with stdin from /dev/null and waits for it.
ProcessResult run_process(const std::vector<std::string>& argv);
// The absolute path of an executable on PATH, or "".
std::string find_on_path(const std::string& program);

struct SlurmSubmission {
  std::vector<int> shards;                // array tasks submitted (empty: nothing left to run)
  std::string array_job, merge_job;       // job ids; empty with dry_run
  std::vector<std::string> commands;      // the sbatch command lines (dry_run: to be run)
  std::string warning;                    // e.g. a node-local output directory
  int tasks = 0;
};

struct SlurmMode {
  bool resume = false;   // only the shards not done (DIR/slurm/sweep.json says how many)
  bool dry_run = false;  // write the scripts, print the sbatch commands, submit nothing
};

// Checks everything first (options, --tasks against `points`, the earlier submission for
// --resume, sbatch on PATH unless dry_run): bad input throws InputError before any file is
// written. `request.tasks` -1 means the default, min(points, 32). A merge sbatch that fails
// cancels the array it was to wait for, so nothing stays half submitted.
SlurmSubmission submit_sweep(SlurmRequest request, const std::string& sweep_hash, std::size_t points,
                             const SlurmMode& mode);

}  // namespace strand::jobs
