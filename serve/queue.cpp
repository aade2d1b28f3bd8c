// The queue's entries and actions: what each state allows, one sender thread per serial port
// (a port runs one entry at a time), and the JSON the page and GET /api/queue show.
#include "serve/queue.h"

#include <algorithm>
#include <cmath>
#include <thread>

#include "serve/api_state.h"
#include "serve/queue_live.h"

namespace strand::serve {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

bool finished(const std::string& state) { return state == "done" || state == "cancelled"; }

bool resumable(const std::string& state) {
  return state == "paused" || state == "failed" || state == "interrupted";
}

// One key per device, whatever the spelling (/dev/serial/by-id/... links to /dev/ttyUSB0).
std::string port_key(const std::string& path) {
  std::error_code ec;
  const fs::path c = fs::canonical(path, ec);
  return ec ? path : c.string();
}

}  // namespace

Queue::Queue(const fs::path& data_dir, bool may_run)
    : dir_(data_dir), may_run_(may_run), store_((data_dir / "strand.sqlite").string()) {
  for (QueueRow& r : store_.rows()) {
    live_[r.id] = std::make_unique<Live>();
    rows_[r.id] = std::move(r);
  }
}

Queue::~Queue() {
  std::vector<Port*> ports;
  {
    const std::lock_guard<std::mutex> lock(mu_);
    stopping_ = true;
    for (auto& [key, p] : ports_) {
      p->pause = true;
      ports.push_back(p.get());
    }
  }
  for (Port* p : ports) {
    if (p->thread.joinable()) p->thread.join();
  }
  events_.close();
}

json Queue::add(QueueRow row) {
  const std::lock_guard<std::mutex> lock(mu_);
  const auto waiting = std::count_if(rows_.begin(), rows_.end(), [](const auto& kv) { return !finished(kv.second.state); });
  if (waiting >= kMaxQueueEntries) {
    throw HttpError(409, "the queue holds " + std::to_string(kMaxQueueEntries) +
                             " entries not done or cancelled, the most it takes; cancel some first");
  }
  row.state = "queued";
  row.id = store_.insert(row);
  store_.save_machine({row.machine, row.port, row.firmware, row.baud});
  store_.prune_finished(kKeepFinishedEntries);
  std::map<std::int64_t, QueueRow> kept;
  for (QueueRow& r : store_.rows()) kept[r.id] = std::move(r);
  for (auto it = rows_.begin(); it != rows_.end();) {
    if (kept.count(it->first)) {
      ++it;
    } else {
      live_.erase(it->first);
      it = rows_.erase(it);
    }
  }
  rows_[row.id] = kept.at(row.id);
  live_[row.id] = std::make_unique<Live>();
  const json j = entry_json(row.id);
  events_.publish("entry", dump(j));
  return j;
}

json Queue::list() {
  const std::lock_guard<std::mutex> lock(mu_);
  json entries = json::array();
  for (const auto& [id, r] : rows_) entries.push_back(entry_json(id));
  json machines = json::array();
  for (const MachinePort& m : store_.machines()) {
    machines.push_back({{"name", m.name}, {"port", m.port}, {"baud", m.baud}, {"firmware", m.firmware}});
  }
  return {{"entries", entries}, {"machines", machines}};
}

json Queue::entry_json(std::int64_t id) {
  const QueueRow& r = rows_.at(id);
  const Live& l = *live_.at(id);
  const double percent = r.total > 0 ? std::round(1000.0 * static_cast<double>(r.acked) / static_cast<double>(r.total)) / 10.0 : 0.0;
  json j = {{"id", r.id},           {"created", r.created}, {"job", r.job},
            {"job_name", r.job_name}, {"file", r.file},     {"machine", r.machine},
            {"port", r.port},       {"baud", r.baud},       {"firmware", r.firmware},
            {"state", r.state},     {"line", r.line},       {"resume_line", r.resume_line},
            {"acked", r.acked},     {"total", r.total},     {"percent", r.state == "done" ? 100.0 : percent},
            {"message", r.message}, {"messages", l.messages}};
  j["time_left_s"] = l.time_left_s >= 0 ? json(std::round(l.time_left_s)) : json();
  j["stopping"] = r.state == "running" && (l.pause || l.cancel);
  j["homing"] = l.homing;
  // Snapshots reach a page by two ways (an action's answer, the event stream) in either order:
  // "rev" tells which is newer.
  j["rev"] = ++rev_;
  return j;
}

void Queue::publish(std::int64_t id, bool progress_only) {
  std::string data;
  {
    const std::lock_guard<std::mutex> lock(mu_);
    const auto it = live_.find(id);
    if (it == live_.end()) return;
    Live& l = *it->second;
    const auto now = std::chrono::steady_clock::now();
    if (progress_only && now - l.last_event < std::chrono::milliseconds(kProgressEventMs)) return;
    l.last_event = now;
    data = dump(entry_json(id));
  }
  events_.publish("entry", data);
}

void Queue::launch(std::int64_t id, const std::string& kind) {
  if (!may_run_) throw HttpError(409, "this server does not run jobs");
  if (stopping_) throw HttpError(503, "the server is stopping");
  QueueRow& r = rows_.at(id);
  std::unique_ptr<Port>& p = ports_[port_key(r.port)];
  if (!p) p = std::make_unique<Port>();
  if (p->busy) {
    throw HttpError(409, "port " + r.port + " is busy with queue entry " + std::to_string(p->entry) +
                             "; pause or cancel it first");
  }
  if (p->thread.joinable()) p->thread.join();  // it has finished: busy is cleared last
  p->busy = true;
  p->entry = id;
  p->pause = false;
  Live& l = *live_.at(id);
  l.pause = l.cancel = false;
  l.messages.clear();
  if (kind == "home") {
    l.homing = true;
  } else {
    r.state = "running";
    r.message.clear();
    store_.update(r);
  }
  p->thread = std::thread([this, id, kind, port = p.get()] { run(id, kind, port); });
}

json Queue::act(std::int64_t id, const std::string& action) {
  json j;
  {
    const std::lock_guard<std::mutex> lock(mu_);
    const auto it = rows_.find(id);
    if (it == rows_.end()) throw HttpError(404, "no queue entry " + std::to_string(id) + " (GET /api/queue lists them)");
    QueueRow& r = it->second;
    Live& l = *live_.at(id);
    const auto refuse = [&](const std::string& needs) {
      return HttpError(409, "queue entry " + std::to_string(id) + " is " + r.state + ": " + action + " needs " + needs);
    };
    if (action == "start") {
      if (r.state != "queued") throw refuse("a queued entry (resume goes on from a stop)");
      launch(id, "run");
    } else if (action == "resume") {
      if (!resumable(r.state)) throw refuse("a paused, failed or interrupted entry");
      launch(id, "run");
    } else if (action == "pause") {
      if (r.state != "running") throw refuse("a running entry");
      l.pause = true;
      ports_.at(port_key(r.port))->pause = true;
    } else if (action == "cancel") {
      if (finished(r.state)) throw refuse("an entry not done or cancelled");
      if (r.state == "running") {
        l.cancel = true;
        ports_.at(port_key(r.port))->pause = true;
      } else {
        r.state = "cancelled";
        r.message = "cancelled";
        store_.update(r);
      }
    } else if (action == "home") {
      if (r.state == "running") throw refuse("its port idle (pause or cancel first)");
      launch(id, "home");
    } else {
      throw HttpError(404, "no queue action " + action.substr(0, 40) + " (start, pause, resume, cancel, home)");
    }
    j = entry_json(id);
  }
  events_.publish("entry", dump(j));
  return j;
}

}  // namespace strand::serve
