// The machine queue of the workbench: G-code files of saved jobs waiting per machine, each
// started, paused, resumed or cancelled by hand and streamed to its serial port by one sender
// thread per port with the streamer and resume logic of `strand send` (machines/send). Every
// change is in SQLite at once (the last acknowledged line on every acknowledgement), so a
// restarted server finds a job it was streaming "interrupted" there, resumable from it.
// Changes are published on an EventHub for GET /api/events.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <nlohmann/json.hpp>
#include <string>

#include "serve/queue_events.h"
#include "serve/queue_store.h"

namespace strand::serve {

// Entries not finished (queued, running, paused, failed, interrupted); more are refused.
inline constexpr int kMaxQueueEntries = 100;
// Finished entries (done, cancelled) kept for the page's history.
inline constexpr int kKeepFinishedEntries = 50;
// Firmware messages kept per entry for the page.
inline constexpr std::size_t kKeptFirmwareMessages = 20;
// Progress events per entry at most this often (state changes are published at once), ms.
inline constexpr int kProgressEventMs = 100;

class Queue {
 public:
  // `data_dir` holds strand.sqlite and jobs/N/ (the files sent); `may_run` false: nothing is
  // ever sent (the fuzz target).
  Queue(const std::filesystem::path& data_dir, bool may_run);
  ~Queue();  // pauses running jobs (bounded waits), marks them interrupted, joins the senders
  Queue(const Queue&) = delete;
  Queue& operator=(const Queue&) = delete;

  // A new queued entry (state, job, file, machine, port, baud, firmware set by the caller,
  // checked); the machine's connection is saved. Throws HttpError 409 when the queue is full.
  nlohmann::json add(QueueRow row);
  // {"entries": [...], "machines": [...]}
  nlohmann::json list();
  // The connection saved for a machine profile by its last queued entry.
  std::optional<MachinePort> saved_machine(const std::string& machine) { return store_.machine(machine); }
  // "start", "pause", "resume", "cancel" or "home" on entry `id`; answers the entry. Throws
  // HttpError 404 (no entry), 409 (not in a state for it, or its port is busy).
  nlohmann::json act(std::int64_t id, const std::string& action);
  EventHub& events() { return events_; }

  struct Port;
  struct Live;

 private:
  nlohmann::json entry_json(std::int64_t id);  // mu_ held
  void launch(std::int64_t id, const std::string& kind);  // mu_ held
  void run(std::int64_t id, const std::string& kind, Port* port);
  void publish(std::int64_t id, bool progress_only);

  std::filesystem::path dir_;
  bool may_run_;
  QueueStore store_;
  EventHub events_;
  std::mutex mu_;
  std::uint64_t rev_ = 0;  // numbers every entry snapshot, so a page keeps the newest
  std::map<std::int64_t, QueueRow> rows_;
  std::map<std::int64_t, std::unique_ptr<Live>> live_;    // what only memory holds, per entry
  std::map<std::string, std::unique_ptr<Port>> ports_;    // by canonical device path
  bool stopping_ = false;
};

}  // namespace strand::serve
