// `strand sweep`: run a sweep file into a directory (optionally one shard of it), or merge
// shard manifests with --merge.
#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <memory>

#include "cli/commands.h"
#include "cli/progress.h"
#include "jobs/sweep_manifest.h"
#include "jobs/sweep_runner.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"
#include "slicer/json_input.h"

namespace strand::cli {

namespace {

struct SweepArgs {
  std::vector<std::string> inputs;  // the sweep file, or shard manifests with --merge
  std::string dir;
  int jobs = 0;
  std::string shard = "1/1";
  bool merge = false;
  bool no_previews = false;
};

nlohmann::json read_json(const std::string& path, const std::string& what) {
  return slicer::parse_json(slicer::read_file(path), what + " = " + path);
}

int run(const SweepArgs& a) {
  if (a.inputs.size() != 1) throw InputError("sweep: give exactly one sweep file (or --merge)");
  if (a.jobs < 0) throw InputError("-j = " + std::to_string(a.jobs) + ": must be >= 1 (0 = every core)");
  const nlohmann::json source = read_json(a.inputs[0], "sweep");
  const SweepSpec spec = sweep_spec_from_json(source);
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
  const std::vector<std::string> paths = a.inputs.empty() ? shard_files(a.dir) : a.inputs;
  std::vector<nlohmann::json> shards;
  for (const auto& p : paths) shards.push_back(read_json(p, "--merge"));
  const nlohmann::json m = merge_manifests(shards, paths);
  std::filesystem::create_directories(a.dir);
  write_manifest(m, a.dir, Shard{});
  std::cout << "sweep: merged " << paths.size() << " shard(s), " << m.at("points").size() << " point(s) -> "
            << (std::filesystem::path(a.dir) / "manifest.json").string() << "\n";
  return 0;
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
  sub->callback([&action, a] { action = [a] { return a->merge ? merge(*a) : run(*a); }; });
}

}  // namespace strand::cli
