// sbatch through posix_spawnp and pipes; the submission record.
#include "jobs/sweep_slurm_submit.h"

#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <filesystem>

#include "slicer/file_io.h"
#include "slicer/input_error.h"

extern char** environ;

namespace strand::jobs {

namespace fs = std::filesystem;

namespace {

constexpr int kDefaultMaxTasks = 32;

std::string first_line(const std::string& text) {
  const std::string line = text.substr(0, text.find('\n'));
  return line.empty() ? "(no message)" : line;
}

// `sbatch --parsable` prints "id" or "id;cluster".
std::string job_id(const ProcessResult& r, const std::string& what) {
  std::string id = r.out.substr(0, r.out.find_first_of(";\n"));
  if (r.exit_code != 0 || id.empty() || !std::all_of(id.begin(), id.end(), ::isdigit)) {
    throw InputError("--slurm: sbatch refused the " + what + ": " + first_line(r.err.empty() ? r.out : r.err));
  }
  return id;
}

// Directories every node has its own copy of: a sweep written there is lost to the others.
bool node_local(const std::string& dir) {
  for (const char* local : {"/tmp", "/var/tmp", "/dev/shm", "/run"}) {
    const std::string l = local;
    if (dir == l || dir.rfind(l + "/", 0) == 0) return true;
  }
  return false;
}

}  // namespace

std::string find_on_path(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "";
  std::size_t start = 0;
  while (start <= dirs.size()) {
    const std::size_t end = std::min(dirs.find(':', start), dirs.size());
    const std::string d = dirs.substr(start, end - start);
    const std::string candidate = (d.empty() ? std::string(".") : d) + "/" + program;
    if (::access(candidate.c_str(), X_OK) == 0 && fs::is_regular_file(candidate)) return fs::absolute(candidate).string();
    start = end + 1;
  }
  return "";
}

ProcessResult run_process(const std::vector<std::string>& argv) {
  ProcessResult r;
  int out[2], err[2];
  if (::pipe2(out, O_CLOEXEC) != 0) return r;
  if (::pipe2(err, O_CLOEXEC) != 0) {
    ::close(out[0]);
    ::close(out[1]);
    return r;
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, out[1], 1);
  posix_spawn_file_actions_adddup2(&actions, err[1], 2);
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = ::posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(out[1]);
  ::close(err[1]);
  // Both pipes read together: a child filling one while we block on the other would hang.
  pollfd fds[2] = {{out[0], POLLIN, 0}, {err[0], POLLIN, 0}};
  std::string* sinks[2] = {&r.out, &r.err};
  int open_pipes = spawned == 0 ? 2 : 0;
  while (open_pipes > 0) {
    if (::poll(fds, 2, -1) < 0) {
      if (errno == EINTR) continue;
      break;
    }
    for (int i = 0; i < 2; ++i) {
      if (fds[i].fd < 0 || !(fds[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
      char buffer[4096];
      const ssize_t n = ::read(fds[i].fd, buffer, sizeof buffer);
      if (n > 0) {
        sinks[i]->append(buffer, static_cast<std::size_t>(n));
      } else if (n == 0 || errno != EINTR) {
        fds[i].fd = -1;
        --open_pipes;
      }
    }
  }
  ::close(out[0]);
  ::close(err[0]);
  if (spawned != 0) {
    r.exit_code = 127;
    r.err = argv[0] + ": cannot be started";
    return r;
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return r;
}

SlurmSubmission submit_sweep(SlurmRequest r, const std::string& sweep_hash, std::size_t points, const SlurmMode& mode) {
  SlurmSubmission s;
  nlohmann::json record = read_submission(r.dir);
  if (mode.resume) {
    if (record.is_null()) {
      throw InputError("--resume: " + slurm_dir(r.dir) + "/sweep.json not found: nothing was submitted to -o = " + r.dir +
                       " (submit without --resume)");
    }
    if (record.value("sweep_hash", "") != sweep_hash) {
      throw InputError("--resume: the sweep file differs from the one submitted to -o = " + r.dir +
                       " (" + record.value("spec", "") + "); submit it without --resume");
    }
    const int submitted = record["tasks"].get<int>();
    if (r.tasks >= 0 && r.tasks != submitted) {
      throw InputError("--tasks = " + std::to_string(r.tasks) + ": --resume keeps the " + std::to_string(submitted) +
                       " tasks of the first submission (the journals are per shard)");
    }
    r.tasks = submitted;
  } else if (r.tasks < 0) {
    r.tasks = static_cast<int>(std::min<std::size_t>(points, kDefaultMaxTasks));
  }
  check_slurm_request(r, points);
  if (!mode.dry_run && find_on_path("sbatch").empty()) {
    throw InputError("--slurm: sbatch not found on PATH (run on a machine with the Slurm client commands, or use --dry-run)");
  }
  s.tasks = r.tasks;
  if (mode.resume) {
    s.shards = shards_not_done(r.dir, r.tasks, sweep_hash);
    if (s.shards.empty()) return s;
  } else {
    for (int i = 1; i <= r.tasks; ++i) s.shards.push_back(i);
  }
  if (node_local(r.dir)) {
    s.warning = "warning: -o = " + r.dir + " is node-local on most clusters; the tasks and the merge must all see it";
  }
  fs::create_directories(slurm_dir(r.dir));
  slicer::write_file_atomic(slurm_dir(r.dir) + "/sweep.sbatch", array_script(r));
  slicer::write_file_atomic(slurm_dir(r.dir) + "/merge.sbatch", merge_script(r));
  const auto array_argv = array_sbatch_argv(r, s.shards);
  if (mode.dry_run) {
    s.commands = {command_line(array_argv), command_line(merge_sbatch_argv(r, "ARRAY_JOB_ID"))};
    return s;
  }
  s.array_job = job_id(run_process(array_argv), "array job");
  const auto merge_argv = merge_sbatch_argv(r, s.array_job);
  const ProcessResult merge = run_process(merge_argv);
  try {
    s.merge_job = job_id(merge, "merge job");
  } catch (const InputError&) {
    run_process({"scancel", s.array_job});
    throw;
  }
  s.commands = {command_line(array_argv), command_line(merge_argv)};
  if (!mode.resume || record.is_null()) {
    record = {{"spec", r.spec}, {"tasks", r.tasks}, {"sweep_hash", sweep_hash}, {"submissions", nlohmann::json::array()}};
  }
  record["strand"] = r.strand;
  record["submissions"].push_back({{"array", s.array_job}, {"merge", s.merge_job}, {"shards", array_ranges(s.shards)}});
  slicer::write_file_atomic(slurm_dir(r.dir) + "/sweep.json", record.dump(2) + "\n");
  return s;
}

}  // namespace strand::jobs
