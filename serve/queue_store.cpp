// SQLite access for the machine queue: prepared statements, one connection behind a mutex,
// WAL with synchronous=NORMAL (a commit survives the process being killed; progress is
// written on every acknowledged line).
#include "serve/queue_store.h"

#include <sqlite3.h>

#include <stdexcept>

#include "serve/sqlite_db.h"
#include "slicer/input_error.h"

namespace strand::serve {

namespace {

using sqlite::Statement;

const char* const kSchema =
    "PRAGMA journal_mode=WAL;"
    "PRAGMA synchronous=NORMAL;"
    "CREATE TABLE IF NOT EXISTS queue ("
    " id INTEGER PRIMARY KEY AUTOINCREMENT,"
    " created TEXT NOT NULL DEFAULT (strftime('%Y-%m-%dT%H:%M:%SZ','now')),"
    " job INTEGER NOT NULL, job_name TEXT NOT NULL, file TEXT NOT NULL, machine TEXT NOT NULL,"
    " port TEXT NOT NULL, baud INTEGER NOT NULL, firmware TEXT NOT NULL,"
    " state TEXT NOT NULL, line INTEGER NOT NULL DEFAULT 0, resume_line INTEGER NOT NULL DEFAULT 0,"
    " acked INTEGER NOT NULL DEFAULT 0, total INTEGER NOT NULL DEFAULT 0, message TEXT NOT NULL DEFAULT '');"
    "CREATE TABLE IF NOT EXISTS queue_machines ("
    " name TEXT PRIMARY KEY, port TEXT NOT NULL, baud INTEGER NOT NULL, firmware TEXT NOT NULL);"
    // a job still streaming when the server stopped: resumable from its last acknowledged line
    "UPDATE queue SET state = 'interrupted',"
    " message = 'the server stopped while it ran; last acknowledged line ' || line"
    " WHERE state = 'running';";

const char* const kColumns =
    "SELECT id, created, job, job_name, file, machine, port, baud, firmware, state, line, resume_line,"
    " acked, total, message FROM queue ";

QueueRow row_of(Statement& st) {
  QueueRow r;
  r.id = st.integer(0);
  r.created = st.text(1);
  r.job = st.integer(2);
  r.job_name = st.text(3);
  r.file = st.text(4);
  r.machine = st.text(5);
  r.port = st.text(6);
  r.baud = static_cast<int>(st.integer(7));
  r.firmware = st.text(8);
  r.state = st.text(9);
  r.line = static_cast<int>(st.integer(10));
  r.resume_line = static_cast<int>(st.integer(11));
  r.acked = st.integer(12);
  r.total = st.integer(13);
  r.message = st.text(14);
  return r;
}

}  // namespace

QueueStore::QueueStore(const std::string& path) : db_(sqlite::open(path, kSchema, " for the queue")) {}

QueueStore::~QueueStore() { sqlite3_close(db_); }

std::int64_t QueueStore::insert(const QueueRow& r) {
  const std::lock_guard<std::mutex> lock(mu_);
  Statement st(db_,
               "INSERT INTO queue (job, job_name, file, machine, port, baud, firmware, state)"
               " VALUES (?, ?, ?, ?, ?, ?, ?, ?)");
  st.bind_all(r.job, r.job_name, r.file, r.machine, r.port, r.baud, r.firmware, r.state);
  st.step();
  return sqlite3_last_insert_rowid(db_);
}

void QueueStore::update(const QueueRow& r) {
  const std::lock_guard<std::mutex> lock(mu_);
  Statement st(db_,
               "UPDATE queue SET job_name = ?, file = ?, machine = ?, port = ?, baud = ?, firmware = ?,"
               " state = ?, line = ?, resume_line = ?, acked = ?, total = ?, message = ? WHERE id = ?");
  st.bind_all(r.job_name, r.file, r.machine, r.port, r.baud, r.firmware, r.state, r.line,
              r.resume_line, r.acked, r.total, r.message, r.id);
  st.step();
}

void QueueStore::progress(std::int64_t id, int line, int resume_line, std::int64_t acked) {
  const std::lock_guard<std::mutex> lock(mu_);
  Statement st(db_, "UPDATE queue SET line = ?, resume_line = ?, acked = ? WHERE id = ?");
  st.bind_all(line, resume_line, acked, id);
  st.step();
}

std::vector<QueueRow> QueueStore::rows() {
  const std::lock_guard<std::mutex> lock(mu_);
  Statement st(db_, (std::string(kColumns) + "ORDER BY id").c_str());
  std::vector<QueueRow> out;
  while (st.step()) out.push_back(row_of(st));
  return out;
}

void QueueStore::prune_finished(int keep) {
  const std::lock_guard<std::mutex> lock(mu_);
  Statement st(db_,
               "DELETE FROM queue WHERE id IN (SELECT id FROM queue WHERE state IN ('done', 'cancelled')"
               " ORDER BY id DESC LIMIT -1 OFFSET ?)");
  st.bind_all(keep);
  st.step();
}

void QueueStore::save_machine(const MachinePort& m) {
  const std::lock_guard<std::mutex> lock(mu_);
  Statement st(db_, "INSERT OR REPLACE INTO queue_machines (name, port, baud, firmware) VALUES (?, ?, ?, ?)");
  st.bind_all(m.name, m.port, m.baud, m.firmware);
  st.step();
}

std::vector<MachinePort> QueueStore::machines() {
  const std::lock_guard<std::mutex> lock(mu_);
  Statement st(db_, "SELECT name, port, baud, firmware FROM queue_machines ORDER BY name");
  std::vector<MachinePort> out;
  while (st.step()) out.push_back({st.text(0), st.text(1), st.text(3), static_cast<int>(st.integer(2))});
  return out;
}

std::optional<MachinePort> QueueStore::machine(const std::string& name) {
  for (const MachinePort& m : machines()) {
    if (m.name == name) return m;
  }
  return std::nullopt;
}

}  // namespace strand::serve
