// The machine queue's rows in SQLite (DIR/strand.sqlite, tables `queue` and `queue_machines`),
// on a connection of its own so the senders' progress writes never wait behind the gallery.
// A row that says "running" when the store opens was cut off by a stopped server: it becomes
// "interrupted", keeping the last line the firmware acknowledged.
#pragma once

#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

struct sqlite3;

namespace strand::serve {

struct QueueRow {
  std::int64_t id = 0;
  std::string created;       // UTC, "2026-01-31T12:00:00Z"
  std::int64_t job = 0;      // the saved job whose file is sent
  std::string job_name;
  std::string file;          // a name from the job's file list
  std::string machine;       // the job's machine profile
  std::string port;          // serial device path
  int baud = 115200;
  std::string firmware;      // marlin, reprap, klipper, grbl
  std::string state;         // queued, running, paused, failed, interrupted, done, cancelled
  int line = 0;              // file line of the last command the firmware acknowledged
  int resume_line = 0;       // file line to go on from (0: from the start)
  std::int64_t acked = 0;    // commands of the file acknowledged
  std::int64_t total = 0;    // commands in the file (0 until it first ran)
  std::string message;       // why it stopped, in one line
};

// A machine's saved connection.
struct MachinePort {
  std::string name, port, firmware;
  int baud = 115200;
};

class QueueStore {
 public:
  // Opens the database at `path` (created by Store); throws InputError when it cannot.
  explicit QueueStore(const std::string& path);
  ~QueueStore();
  QueueStore(const QueueStore&) = delete;
  QueueStore& operator=(const QueueStore&) = delete;

  std::int64_t insert(const QueueRow& row);  // returns the id; `created` is set by SQLite
  void update(const QueueRow& row);          // every column but id, job and created
  // The progress columns only: called on every acknowledgement while a job runs.
  void progress(std::int64_t id, int line, int resume_line, std::int64_t acked);
  std::vector<QueueRow> rows();  // oldest first
  // Removes finished rows (done, cancelled) beyond the newest `keep` of them.
  void prune_finished(int keep);

  void save_machine(const MachinePort& m);
  std::vector<MachinePort> machines();  // by name
  std::optional<MachinePort> machine(const std::string& name);

 private:
  std::mutex mu_;
  sqlite3* db_ = nullptr;
};

}  // namespace strand::serve
