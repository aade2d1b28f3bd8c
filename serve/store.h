// The workbench's index of jobs in SQLite (DIR/strand.sqlite): one row per generated job,
// saved (in the gallery, with a name) or not (a live preview of the design page, kept only
// for the newest few). The files of job N live in DIR/jobs/N/ under names the server chose.
#pragma once

#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

struct sqlite3;

namespace strand::serve {

struct JobRow {
  std::int64_t id = 0;
  std::string created;  // UTC, "2026-01-31T12:00:00Z"
  std::string name;     // "" for unsaved jobs
  bool saved = false;
  std::string status;   // "running", "ok", "failed"
  std::string job;      // the job JSON as given (without output paths)
  std::string result;   // the result JSON once done ("" while running)
};

class Store {
 public:
  // Opens or creates DIR/strand.sqlite; throws InputError when it cannot.
  explicit Store(const std::string& path);
  ~Store();
  Store(const Store&) = delete;
  Store& operator=(const Store&) = delete;

  std::int64_t insert(bool saved, const std::string& name, const std::string& job);
  void finish(std::int64_t id, const std::string& status, const std::string& result);
  std::optional<JobRow> get(std::int64_t id);
  std::vector<JobRow> saved_jobs();  // newest first
  bool remove(std::int64_t id);
  // Ids of the unsaved jobs older than the newest `keep`.
  std::vector<std::int64_t> stale_unsaved(int keep);

 private:
  std::mutex mu_;
  sqlite3* db_ = nullptr;
};

}  // namespace strand::serve
