// Reading the progress of a sweep back from its files; nothing is written or locked for good.
#include "jobs/sweep_status.h"

#include <filesystem>
#include <regex>
#include <set>

#include "jobs/sweep_journal.h"
#include "jobs/sweep_manifest.h"
#include "jobs/sweep_slurm.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"
#include "slicer/json_input.h"

namespace strand::jobs {

namespace fs = std::filesystem;

namespace {

nlohmann::json read_manifest(const fs::path& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return nullptr;
  nlohmann::json m = nlohmann::json::parse(slicer::read_file(path.string()), nullptr, false);
  return m.is_object() && m.contains("points") && m["points"].is_array() ? m : nlohmann::json();
}

// The shard counts the file names show: manifest-shard-I-of-N.* -> N, manifest.* -> 1.
std::set<int> counts_on_disk(const std::string& dir) {
  static const std::regex shard_file("manifest-shard-[0-9]+-of-([0-9]+)\\.(json|journal\\.jsonl)");
  std::set<int> counts;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    std::smatch m;
    if (std::regex_match(name, m, shard_file)) counts.insert(std::stoi(m[1].str()));
    if (name == "manifest.journal.jsonl") counts.insert(1);
  }
  if (counts.empty() && fs::is_regular_file(fs::path(dir) / "manifest.json", ec)) counts.insert(1);
  return counts;
}

// Every point of the sweep, from whatever says: a manifest, a journal header, the sweep file.
std::size_t sweep_points(const std::string& dir, int count, const nlohmann::json& submission) {
  for (int i = 1; i <= count; ++i) {
    const nlohmann::json m = read_manifest(fs::path(dir) / manifest_file_name(Shard{i, count}));
    if (!m.is_null() && m.contains("sweep")) return m["sweep"].value("points", std::size_t{0});
    const std::size_t n = journal_sweep_points((fs::path(dir) / journal_file_name(Shard{i, count})).string());
    if (n > 0) return n;
  }
  if (!submission.is_null()) {
    try {
      const std::string spec = submission.value("spec", "");
      return expand_points(sweep_spec_from_json(slicer::parse_json(slicer::read_file(spec), spec))).size();
    } catch (const std::exception&) {
      return 0;  // the sweep file moved or changed: the shard sizes stay unknown
    }
  }
  return 0;
}

}  // namespace

const char* state_name(ShardState s) {
  switch (s) {
    case ShardState::NotStarted: return "not started";
    case ShardState::Running: return "running";
    case ShardState::Stopped: return "stopped";
    case ShardState::Finished: return "finished";
  }
  return "";
}

SweepStatus sweep_status(const std::string& dir) {
  const nlohmann::json submission = read_submission(dir);
  int count = 0;
  if (!submission.is_null()) {
    count = submission["tasks"].get<int>();
  } else {
    const std::set<int> counts = counts_on_disk(dir);
    if (counts.empty()) throw InputError("--status: -o = " + dir + " holds no sweep (no manifest, journal or Slurm submission)");
    if (counts.size() > 1) {
      throw InputError("--status: -o = " + dir + " holds shards of " + std::to_string(counts.size()) +
                       " different shard counts; give each its own directory");
    }
    count = *counts.begin();
  }
  SweepStatus status;
  status.points = sweep_points(dir, count, submission);
  for (int i = 1; i <= count; ++i) {
    ShardStatus s;
    s.shard = Shard{i, count};
    const auto n = static_cast<std::size_t>(count);
    s.points = status.points / n + (static_cast<std::size_t>(i - 1) < status.points % n ? 1 : 0);
    const nlohmann::json m = read_manifest(fs::path(dir) / manifest_file_name(s.shard));
    const std::string journal = (fs::path(dir) / journal_file_name(s.shard)).string();
    std::error_code ec;
    if (journal_in_use(journal)) {
      s.state = ShardState::Running;
      s.done = journal_rows(journal).size();
    } else if (!m.is_null() && !fs::exists(journal, ec)) {
      s.state = ShardState::Finished;
      for (const auto& row : m["points"]) {
        const std::string st = row.value("status", "");
        s.done += st == "ok" || st == "dropped";
        s.failed += st == "failed";
      }
      s.points = std::max(s.points, s.done + s.failed);
    } else if (fs::exists(journal, ec)) {
      s.state = ShardState::Stopped;  // killed, pre-empted or out of time before its manifest
      s.done = journal_rows(journal).size();
    }
    s.done = std::min(s.done, s.points - s.failed);
    status.shards.push_back(s);
  }
  status.merged = count > 1 && fs::is_regular_file(fs::path(dir) / "manifest.json");
  return status;
}

}  // namespace strand::jobs
