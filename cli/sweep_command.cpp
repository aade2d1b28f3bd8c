// `strand sweep`: run a sweep file into a directory (optionally one shard of it), merge
// shard manifests with --merge, submit it to Slurm with --slurm, report progress with --status.
#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <memory>

#include "cli/commands.h"
#include "cli/progress_bar.h"
#include "jobs/content_hash.h"
#include "jobs/sweep_manifest.h"
#include "jobs/sweep_runner.h"
#include "jobs/sweep_slurm_submit.h"
#include "jobs/sweep_status.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"
#include "slicer/json_input.h"

namespace strand::cli {

using jobs::Shard;
using jobs::ShardState;
using jobs::SlurmMode;
using jobs::SlurmRequest;
using jobs::SlurmSubmission;
using jobs::SweepOptions;
using jobs::SweepProgress;
using jobs::SweepResult;
using jobs::SweepSpec;
using jobs::SweepStatus;
using jobs::array_ranges;
using jobs::command_line;
using jobs::expand_points;
using jobs::failed_point_lines;
using jobs::fnv1a_hex;
using jobs::manifest_file_name;
using jobs::merge_manifests;
using jobs::missing_shards_message;
using jobs::parse_shard;
using jobs::run_sweep;
using jobs::slurm_dir;
using jobs::state_name;
using jobs::submit_sweep;
using jobs::sweep_spec_from_json;
using jobs::sweep_status;
using jobs::write_manifest;

namespace {

struct SweepArgs {
  std::vector<std::string> inputs;  // the sweep file, or shard manifests with --merge
  std::string dir;
  int jobs = 0;
  std::string shard = "1/1";
  bool merge = false;
  bool no_previews = false;
  bool status = false;
  // --slurm and its options
  bool slurm = false, resume = false, dry_run = false;
  int tasks = -1;
  std::string partition, time, mem;
  std::vector<std::string> sbatch_args;
};

// Options that mean nothing without --slurm are refused rather than ignored.
void check_slurm_flags(const SweepArgs& a) {
  if (a.slurm) {
    if (a.shard != "1/1") throw InputError("--shard = " + a.shard + ": --slurm gives each array task its shard");
    return;
  }
  const std::pair<bool, const char*> only[] = {{a.tasks != -1, "--tasks"}, {!a.partition.empty(), "--partition"},
                                               {!a.time.empty(), "--time"}, {!a.mem.empty(), "--mem"},
                                               {!a.sbatch_args.empty(), "--sbatch-arg"}, {a.resume, "--resume"},
                                               {a.dry_run, "--dry-run"}};
  for (const auto& [given, flag] : only) {
    if (given) throw InputError(std::string(flag) + ": only with --slurm");
  }
}

nlohmann::json read_json(const std::string& path, const std::string& what) {
  return slicer::parse_json(slicer::read_file(path), what + " = " + path);
}

namespace fs = std::filesystem;

int submit(const SweepArgs& a, const nlohmann::json& source, std::size_t points) {
  SlurmRequest r;
  r.strand = fs::read_symlink("/proc/self/exe").string();  // the tasks run this very program
  r.spec = fs::absolute(a.inputs[0]).lexically_normal().string();
  r.dir = fs::absolute(a.dir).lexically_normal().string();
  if (r.dir.size() > 1 && r.dir.back() == '/') r.dir.pop_back();
  r.workdir = fs::current_path().string();
  r.tasks = a.tasks;
  r.partition = a.partition;
  r.time = a.time;
  r.mem = a.mem;
  r.sbatch_args = a.sbatch_args;
  r.previews = !a.no_previews;
  const SlurmSubmission s = submit_sweep(r, fnv1a_hex(source.dump()), points, SlurmMode{a.resume, a.dry_run});
  if (!s.warning.empty()) std::cerr << s.warning << "\n";
  if (s.shards.empty()) {
    std::cout << "sweep: every shard of " << s.tasks << " is done; nothing to resume (merge: strand sweep --merge -o "
              << command_line({a.dir}) << ")\n";
    return 0;
  }
  const std::string tasks = array_ranges(s.shards);
  if (a.dry_run) {
    std::cout << "sweep: " << points << " point(s) in " << s.tasks << " shard(s), array tasks " << tasks << ": wrote "
              << slurm_dir(a.dir) << "/sweep.sbatch and merge.sbatch; submit with:\n";
    for (const auto& c : s.commands) std::cout << "  " << c << "\n";
    return 0;
  }
  std::cout << "sweep: " << points << " point(s) in " << s.tasks << " shard(s): array job " << s.array_job
            << " (tasks " << tasks << "), merge job " << s.merge_job << " after it -> " << (fs::path(a.dir) / "manifest.json").string() << "\n"
            << "watch: squeue -j " << s.array_job << "," << s.merge_job << "; sacct -j " << s.array_job << ","
            << s.merge_job << "; strand sweep --status -o " << command_line({a.dir}) << "\n"
            << "logs: " << slurm_dir(a.dir) << "/task-<I>.log, " << slurm_dir(a.dir) << "/merge.log\n";
  return 0;
}

int status(const SweepArgs& a) {
  if (!a.inputs.empty()) throw InputError("--status: give only -o DIR (the sweep file is not needed)");
  const SweepStatus st = sweep_status(a.dir);
  std::size_t done = 0, failed = 0, running = 0, waiting = 0;
  for (const auto& s : st.shards) {
    done += s.done;
    failed += s.failed;
    (s.state == ShardState::Running ? running : waiting) += s.remaining();
  }
  std::cout << "sweep: " << a.dir << ": " << st.points << " point(s) in " << st.shards.size() << " shard(s): " << done
            << " done, " << running << " running, " << failed << " failed, " << waiting << " waiting"
            << (st.merged ? ", merged" : "") << "\n";
  for (const auto& s : st.shards) {
    std::cout << "shard " << s.shard.index << "/" << s.shard.count << ": " << s.points << " point(s), " << s.done
              << " done, " << (s.state == ShardState::Running ? s.remaining() : 0) << " running, " << s.failed
              << " failed (" << state_name(s.state) << ")\n";
  }
  return failed ? 1 : 0;
}

int run(const SweepArgs& a) {
  if (a.inputs.size() != 1) throw InputError("sweep: give exactly one sweep file (or --merge)");
  if (a.jobs < 0) throw InputError("-j = " + std::to_string(a.jobs) + ": must be >= 1 (0 = every core)");
  check_slurm_flags(a);
  const nlohmann::json source = read_json(a.inputs[0], "sweep");
  const SweepSpec spec = sweep_spec_from_json(source);
  if (a.slurm) return submit(a, source, expand_points(spec).size());
  SweepOptions o;
  o.dir = a.dir;
  o.jobs = a.jobs;
  o.shard = parse_shard(a.shard);
  o.previews = !a.no_previews;
  ProgressBar bar(progress_stream(), ::isatty(STDERR_FILENO) != 0);  // nothing with --quiet
  const SweepResult r = run_sweep(spec, source, o, [&bar](const SweepProgress& p) {
    const auto& row = *p.row;
    const std::string status = row.at("status").get<std::string>();
    bar.update(p.done, p.total, p.failed, row.at("name").get<std::string>(),
               status == "failed" ? "failed: " + row.at("error").get<std::string>() : status);
  });
  bar.finish();
  std::cout << "sweep: " << r.manifest.at("points").size() << " point(s): " << r.ran << " ran, " << r.reused
            << " up to date, " << r.failed << " failed, " << r.dropped << " dropped -> "
            << (std::filesystem::path(a.dir) / manifest_file_name(o.shard)).string() << "\n";
  return r.failed ? 1 : 0;
}

std::vector<std::string> shard_files(const std::string& dir) {
  std::vector<std::string> files;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("manifest-shard-", 0) == 0 && e.path().extension() == ".json") files.push_back(e.path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

int merge(const SweepArgs& a) {
  if (a.inputs.empty()) {  // a submitted sweep: name the tasks that did not finish and their logs
    const std::string missing = missing_shards_message(a.dir);
    if (!missing.empty()) throw InputError(missing);
  }
  const std::vector<std::string> paths = a.inputs.empty() ? shard_files(a.dir) : a.inputs;
  std::vector<nlohmann::json> shards;
  for (const auto& p : paths) shards.push_back(read_json(p, "--merge"));
  const nlohmann::json m = merge_manifests(shards, paths);
  std::filesystem::create_directories(a.dir);
  write_manifest(m, a.dir, Shard{});
  std::cout << "sweep: merged " << paths.size() << " shard(s), " << m.at("points").size() << " point(s) -> "
            << (std::filesystem::path(a.dir) / "manifest.json").string() << "\n";
  const auto failed = failed_point_lines(m, a.dir);
  for (const auto& line : failed) std::cout << line << "\n";
  return failed.empty() ? 0 : 1;
}

}  // namespace

void add_sweep_command(CLI::App& app, Action& action) {
  auto a = std::make_shared<SweepArgs>();
  CLI::App* sub = app.add_subcommand("sweep", "run a parameter sweep file: one G-code per point, manifest, index.html");
  sub->add_option("inputs", a->inputs, "sweep file (JSON); with --merge: shard manifests (default DIR/manifest-shard-*.json)");
  sub->add_option("-o,--output", a->dir, "output directory")->required();
  sub->add_option("-j,--jobs", a->jobs, "parallel points (default: every core)");
  sub->add_option("--shard", a->shard, "run shard I of N (1-based), e.g. --shard $SLURM_ARRAY_TASK_ID/8");
  sub->add_flag("--merge", a->merge, "merge shard manifests into DIR/manifest.json, manifest.csv, index.html");
  sub->add_flag("--no-previews", a->no_previews, "skip the PNG thumbnail and HTML viewer per point");
  sub->add_flag("--status", a->status, "points done / running / failed per shard in DIR, from the journals");
  sub->add_flag("--slurm", a->slurm, "submit as a Slurm job array (one task per shard) and a merge job after it");
  sub->add_option("--tasks", a->tasks, "--slurm: array tasks = shards (default: min(points, 32))");
  sub->add_option("--partition", a->partition, "--slurm: Slurm partition");
  sub->add_option("--time", a->time, "--slurm: time limit per task (HH:MM:SS)");
  sub->add_option("--mem", a->mem, "--slurm: memory per task (e.g. 4G)");
  sub->add_option("--sbatch-arg", a->sbatch_args, "--slurm: one more sbatch option, e.g. --sbatch-arg=--account=lab");
  sub->add_flag("--resume", a->resume, "--slurm: resubmit only the shards with points not done");
  sub->add_flag("--dry-run", a->dry_run, "--slurm: write DIR/slurm/*.sbatch and print the sbatch commands only");
  sub->callback([&action, a] {
    action = [a] { return a->status ? status(*a) : a->merge ? merge(*a) : run(*a); };
  });
}

}  // namespace strand::cli
