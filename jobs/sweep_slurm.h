// `strand sweep --slurm`: a sweep as a Slurm job array, one array task per shard (task I runs
// `strand sweep SPEC -o DIR --shard I/N`), and a merge job that waits for the whole array
// (afterany) and runs `strand sweep --merge -o DIR`. Scripts and the submission record live
// in DIR/slurm/; the task logs are DIR/slurm/task-I.log (appended across resubmissions), the
// merge's DIR/slurm/merge.log. Nothing here runs a program: see sweep_slurm_submit.h.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "jobs/sweep_spec.h"

namespace strand::jobs {

struct SlurmRequest {
  std::string strand;    // absolute path of the strand program the tasks run
  std::string spec;      // absolute path of the sweep file
  std::string dir;       // absolute output directory
  std::string workdir;   // absolute directory the tasks start in (relative profile paths)
  int tasks = -1;        // N: array tasks = shards; -1: the default
  std::string partition, time, mem;   // empty: the cluster's default
  std::vector<std::string> sbatch_args;  // passed to both sbatch calls, never into a script
  bool previews = true;
};

// Checks every option before anything is written or submitted; throws InputError naming the
// option and what it accepts. `points` is the number of points of the sweep.
void check_slurm_request(const SlurmRequest& r, std::size_t points);

// POSIX single quotes: any byte string becomes one shell word.
std::string shell_quote(const std::string& word);
// The array task's script (DIR/slurm/sweep.sbatch) and the merge job's (merge.sbatch).
std::string array_script(const SlurmRequest& r);
std::string merge_script(const SlurmRequest& r);
// "1-4" for consecutive shards, else "2,4".
std::string array_ranges(const std::vector<int>& shards);
// The sbatch command lines, argv[0] = "sbatch"; the job id goes in afterany:<id>.
std::vector<std::string> array_sbatch_argv(const SlurmRequest& r, const std::vector<int>& shards);
std::vector<std::string> merge_sbatch_argv(const SlurmRequest& r, const std::string& array_job);
// A command line as a user would type it (each word shell-quoted when it needs to be).
std::string command_line(const std::vector<std::string>& argv);

std::string slurm_dir(const std::string& dir);          // DIR/slurm
std::string task_log(const std::string& dir, int task);  // DIR/slurm/task-I.log
// DIR/slurm/sweep.json: {"spec", "tasks", "sweep_hash", "strand", "submissions": [{"array",
// "merge", "shards"}]}; null when the directory holds no submission.
nlohmann::json read_submission(const std::string& dir);

// Shards of a sweep of N tasks not done in DIR: no shard manifest, one of another sweep
// (another sweep_hash), or one listing failed points. Their finished points are reused.
std::vector<int> shards_not_done(const std::string& dir, int tasks, const std::string& sweep_hash);

// For the merge of a submitted sweep: one line per missing shard, naming its array task and
// log and the resume command; empty when every shard manifest is there.
std::string missing_shards_message(const std::string& dir);
// One line per failed point of a merged manifest: index, name, error, and for a submitted
// sweep its array task and log.
std::vector<std::string> failed_point_lines(const nlohmann::json& manifest, const std::string& dir);

}  // namespace strand::jobs
