// SQLite access for the workbench: prepared statements, one connection behind a mutex.
#include "serve/store.h"

#include <sqlite3.h>

#include <memory>

#include "serve/sqlite_db.h"
#include "slicer/input_error.h"

namespace strand::serve {

namespace {

using sqlite::Statement;

const char* const kSchema =
    "PRAGMA journal_mode=WAL;"
    "CREATE TABLE IF NOT EXISTS jobs ("
    " id INTEGER PRIMARY KEY AUTOINCREMENT,"
    " created TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%SZ','now')),"
    " name TEXT NOT NULL, saved INTEGER NOT NULL, status TEXT NOT NULL DEFAULT 'running',"
    " job TEXT NOT NULL, result TEXT NOT NULL DEFAULT '');"
    // a job still running when the server stopped never finished
    "UPDATE jobs SET status = 'failed' WHERE status = 'running';";

const char* const kColumns = "SELECT id, created, name, saved, status, job, result FROM jobs ";

JobRow row_of(Statement& st) {
  JobRow r;
  r.id = sqlite3_column_int64(st.s, 0);
  r.created = st.text(1);
  r.name = st.text(2);
  r.saved = sqlite3_column_int(st.s, 3) != 0;
  r.status = st.text(4);
  r.job = st.text(5);
  r.result = st.text(6);
  return r;
}

}  // namespace

Store::Store(const std::string& path) : db_(sqlite::open(path, kSchema, "")) {}

Store::~Store() { sqlite3_close(db_); }

std::int64_t Store::insert(bool saved, const std::string& name, const std::string& job) {
  const std::lock_guard<std::mutex> lock(mu_);
  Statement st(db_, "INSERT INTO jobs (name, saved, job) VALUES (?, ?, ?)");
  st.bind_all(name, saved ? 1 : 0, job);
  st.step();
  return sqlite3_last_insert_rowid(db_);
}

void Store::finish(std::int64_t id, const std::string& status, const std::string& result) {
  const std::lock_guard<std::mutex> lock(mu_);
  Statement st(db_, "UPDATE jobs SET status = ?, result = ? WHERE id = ?");
  st.bind_all(status, result, id);
  st.step();
}

std::optional<JobRow> Store::get(std::int64_t id) {
  const std::lock_guard<std::mutex> lock(mu_);
  Statement st(db_, (std::string(kColumns) + "WHERE id = ?").c_str());
  st.bind_all(id);
  if (!st.step()) return std::nullopt;
  return row_of(st);
}

std::vector<JobRow> Store::saved_jobs() {
  const std::lock_guard<std::mutex> lock(mu_);
  Statement st(db_, (std::string(kColumns) + "WHERE saved = 1 ORDER BY id DESC").c_str());
  std::vector<JobRow> rows;
  while (st.step()) rows.push_back(row_of(st));
  return rows;
}

bool Store::remove(std::int64_t id) {
  const std::lock_guard<std::mutex> lock(mu_);
  Statement st(db_, "DELETE FROM jobs WHERE id = ?");
  st.bind_all(id);
  st.step();
  return sqlite3_changes(db_) > 0;
}

std::vector<std::int64_t> Store::stale_unsaved(int keep) {
  const std::lock_guard<std::mutex> lock(mu_);
  Statement st(db_, "SELECT id FROM jobs WHERE saved = 0 AND status != 'running' ORDER BY id DESC LIMIT -1 OFFSET ?");
  st.bind_all(keep);
  std::vector<std::int64_t> ids;
  while (st.step()) ids.push_back(sqlite3_column_int64(st.s, 0));
  return ids;
}

}  // namespace strand::serve
