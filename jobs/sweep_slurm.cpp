// Slurm scripts, sbatch command lines and the reading of a submitted sweep's state.
#include "jobs/sweep_slurm.h"

#include <filesystem>
#include <regex>

#include "jobs/sweep_journal.h"
#include "jobs/sweep_manifest.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"

namespace strand::jobs {

namespace fs = std::filesystem;

namespace {

bool has_control(const std::string& s) {
  for (const char c : s) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) return true;
  }
  return false;
}

void check_value(const std::string& option, const std::string& value, const char* pattern, const std::string& allowed) {
  if (!value.empty() && !std::regex_match(value, std::regex(pattern))) {
    throw InputError(option + " = " + value + ": must be " + allowed);
  }
}

// Options strand sets itself on the sbatch command line: given twice, sbatch would take the
// user's and the array, its logs or the merge's wait would silently be another.
const char* const kOwnOptions[] = {"--array", "-a", "--output", "-o", "--open-mode", "--dependency",
                                   "-d", "--parsable", "--wrap", "--chdir", "-D"};

// A shell word as written: plain when it is made of characters no shell treats specially.
bool plain_word(const std::string& w) {
  return !w.empty() && std::regex_match(w, std::regex("[A-Za-z0-9_@%+=:,./-]+"));
}

std::string sbatch_header(const SlurmRequest& r, const std::string& job_name, bool limits) {
  std::string h = "#!/bin/sh\n#SBATCH --job-name=" + job_name + "\n";
  if (!r.partition.empty()) h += "#SBATCH --partition=" + r.partition + "\n";
  if (limits && !r.time.empty()) h += "#SBATCH --time=" + r.time + "\n";
  if (limits && !r.mem.empty()) h += "#SBATCH --mem=" + r.mem + "\n";
  return h;
}

std::string shard_manifest(const std::string& dir, int shard, int tasks) {
  return (fs::path(dir) / manifest_file_name(Shard{shard, tasks})).string();
}

}  // namespace

void check_slurm_request(const SlurmRequest& r, std::size_t points) {
  if (r.tasks < 1 || static_cast<std::size_t>(r.tasks) > points) {
    throw InputError("--tasks = " + std::to_string(r.tasks) + ": must be in [1, " + std::to_string(points) +
                     "] (one array task per shard; the sweep has " + std::to_string(points) + " points)");
  }
  // These go into #SBATCH lines, so they must stay one plain line each.
  check_value("--partition", r.partition, "[A-Za-z0-9_.,-]+", "a partition name or a comma list (letters, digits, _ . -)");
  check_value("--time", r.time, "([0-9]+-)?[0-9]+(:[0-9]+){0,2}", "a Slurm time: minutes, HH:MM:SS or D-HH:MM:SS");
  check_value("--mem", r.mem, "[0-9]+[KMGT]?", "a Slurm memory size: digits with K, M, G or T (e.g. 4G)");
  for (const auto& a : r.sbatch_args) {
    if (a.empty() || a[0] != '-' || has_control(a)) {
      throw InputError("--sbatch-arg = " + a + ": must be one sbatch option starting with - (e.g. --account=lab)");
    }
    const std::string name = a.substr(0, a.find('='));
    for (const char* own : kOwnOptions) {
      if (name == own || (name.size() > 2 && name[1] != '-' && name.substr(0, 2) == own)) {
        throw InputError("--sbatch-arg = " + a + ": strand sets " + own + " itself (the array, the logs in DIR/slurm/, the merge's wait)");
      }
    }
  }
  // Slurm expands %A, %a, %j... in --output: a directory with % would log elsewhere.
  if (r.dir.find('%') != std::string::npos || has_control(r.dir)) {
    throw InputError("-o = " + r.dir + ": with --slurm the directory may not contain % or control characters (Slurm log paths)");
  }
}

std::string shell_quote(const std::string& word) {
  std::string q = "'";
  for (const char c : word) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string array_script(const SlurmRequest& r) {
  std::string s = sbatch_header(r, "strand-sweep", true);
  s += "# One array task per shard: task I of N runs the points p with p mod N = I - 1, journals\n"
       "# each finished point and writes manifest-shard-I-of-N.json. strand sweep --slurm submits it\n"
       "# with the array, the log file and any --sbatch-arg on the sbatch command line.\n";
  s += "cd " + shell_quote(r.workdir) + " || exit 1\n";
  s += "exec " + shell_quote(r.strand) + " sweep " + shell_quote(r.spec) + " -o " + shell_quote(r.dir) +
       " --shard \"$SLURM_ARRAY_TASK_ID/" + std::to_string(r.tasks) + "\" -j \"${SLURM_CPUS_PER_TASK:-1}\"" +
       (r.previews ? "" : " --no-previews") + "\n";
  return s;
}

std::string merge_script(const SlurmRequest& r) {
  std::string s = sbatch_header(r, "strand-sweep-merge", false);
  s += "# Runs once every array task has ended (afterany), finished or not: a missing shard or a\n"
       "# failed point is listed with its array task and log.\n";
  s += "cd " + shell_quote(r.workdir) + " || exit 1\n";
  s += "exec " + shell_quote(r.strand) + " sweep --merge -o " + shell_quote(r.dir) + "\n";
  return s;
}

std::string array_ranges(const std::vector<int>& shards) {
  std::string out;
  for (std::size_t i = 0; i < shards.size();) {
    std::size_t j = i;
    while (j + 1 < shards.size() && shards[j + 1] == shards[j] + 1) ++j;
    out += (out.empty() ? "" : ",") + std::to_string(shards[i]);
    if (j > i) out += "-" + std::to_string(shards[j]);
    i = j + 1;
  }
  return out;
}

std::string slurm_dir(const std::string& dir) { return (fs::path(dir) / "slurm").string(); }

std::string task_log(const std::string& dir, int task) {
  return (fs::path(slurm_dir(dir)) / ("task-" + std::to_string(task) + ".log")).string();
}

std::vector<std::string> array_sbatch_argv(const SlurmRequest& r, const std::vector<int>& shards) {
  std::vector<std::string> argv = {"sbatch", "--parsable", "--array=" + array_ranges(shards),
                                   "--output=" + slurm_dir(r.dir) + "/task-%a.log", "--open-mode=append"};
  argv.insert(argv.end(), r.sbatch_args.begin(), r.sbatch_args.end());
  argv.push_back(slurm_dir(r.dir) + "/sweep.sbatch");
  return argv;
}

std::vector<std::string> merge_sbatch_argv(const SlurmRequest& r, const std::string& array_job) {
  std::vector<std::string> argv = {"sbatch", "--parsable", "--dependency=afterany:" + array_job,
                                   "--output=" + slurm_dir(r.dir) + "/merge.log", "--open-mode=append"};
  argv.insert(argv.end(), r.sbatch_args.begin(), r.sbatch_args.end());
  argv.push_back(slurm_dir(r.dir) + "/merge.sbatch");
  return argv;
}

std::string command_line(const std::vector<std::string>& argv) {
  std::string line;
  for (const auto& w : argv) line += (line.empty() ? "" : " ") + (plain_word(w) ? w : shell_quote(w));
  return line;
}

nlohmann::json read_submission(const std::string& dir) {
  const fs::path file = fs::path(slurm_dir(dir)) / "sweep.json";
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) return nullptr;
  const nlohmann::json j = nlohmann::json::parse(slicer::read_file(file.string()), nullptr, false);
  if (!j.is_object() || !j.contains("tasks") || !j["tasks"].is_number_integer() || j["tasks"].get<int>() < 1) {
    throw InputError(file.string() + ": not a strand sweep submission record");
  }
  return j;
}

std::vector<int> shards_not_done(const std::string& dir, int tasks, const std::string& sweep_hash) {
  std::vector<int> out;
  for (int i = 1; i <= tasks; ++i) {
    const std::string path = shard_manifest(dir, i, tasks);
    std::error_code ec;
    bool done = false;
    if (fs::is_regular_file(path, ec)) {
      const nlohmann::json m = nlohmann::json::parse(slicer::read_file(path), nullptr, false);
      done = m.is_object() && m.contains("points") && m.contains("sweep") &&
             m["sweep"].value("sweep_hash", "") == sweep_hash;
      if (done) {
        for (const auto& row : m["points"]) done = done && row.value("status", "") != "failed";
      }
    }
    if (!done) out.push_back(i);
  }
  return out;
}

std::string missing_shards_message(const std::string& dir) {
  const nlohmann::json sub = read_submission(dir);
  if (sub.is_null()) return "";
  const int tasks = sub["tasks"].get<int>();
  std::string missing;
  int count = 0;
  for (int i = 1; i <= tasks; ++i) {
    std::error_code ec;
    if (fs::is_regular_file(shard_manifest(dir, i, tasks), ec)) continue;
    const auto journalled = journal_rows((fs::path(dir) / journal_file_name(Shard{i, tasks})).string()).size();
    missing += (count++ ? "; " : "") + std::string("shard ") + std::to_string(i) + "/" + std::to_string(tasks) +
               " (array task " + std::to_string(i) + ", log " + task_log(dir, i) + ", " + std::to_string(journalled) +
               " point(s) journalled)";
  }
  if (count == 0) return "";
  return "--merge: " + std::to_string(count) + " of " + std::to_string(tasks) + " shards did not finish: " + missing +
         "; resume: strand sweep " + command_line({sub.value("spec", "SPEC")}) + " -o " + command_line({dir}) +
         " --slurm --resume";
}

std::vector<std::string> failed_point_lines(const nlohmann::json& manifest, const std::string& dir) {
  const nlohmann::json sub = read_submission(dir);
  std::vector<std::string> lines;
  for (const auto& row : manifest.at("points")) {
    if (row.value("status", "") != "failed") continue;
    const int index = row.at("index").get<int>();
    std::string line = "failed: point " + std::to_string(index) + " " + row.value("name", "") + ": " + row.value("error", "");
    if (!sub.is_null()) {
      const int task = index % sub["tasks"].get<int>() + 1;
      line += " (array task " + std::to_string(task) + ", log " + task_log(dir, task) + ")";
    }
    lines.push_back(line);
  }
  return lines;
}

}  // namespace strand::jobs
