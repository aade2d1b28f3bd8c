// What the workbench's route handlers share: the HTTP error they throw, JSON answers, path
// pieces, headers, and the server's state (options, data directory, database, workers).
// Handlers of one area (jobs, queue, plot) live in files of their own and are called from
// Api::State::route.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "serve/api.h"
#include "serve/store.h"
#include "serve/worker_pool.h"

namespace strand::jobs {
struct JobSpec;
}

namespace strand::serve {

class Queue;

// Thrown by handlers; Api::handle answers it as {"error": what()} with the status.
class HttpError : public std::runtime_error {
 public:
  HttpError(int status, const std::string& message) : std::runtime_error(message), status(status) {}
  int status;
};

// Compact, one line, never throwing on bytes that are not UTF-8.
std::string dump(const nlohmann::json& j);
Response json_response(int status, const nlohmann::json& j);
Response error(int status, const std::string& message);
// An embedded page ("design.html") as a GET answers it; 405 unless `method` is GET or HEAD.
Response page_response(const std::string& name, const std::string& method);
// "/api/jobs/3" -> {"api", "jobs", "3"}; a path not starting with '/' matches no route.
std::vector<std::string> split_path(const std::string& path);
// A job id from the path, 404 unless digits.
std::int64_t parse_id(const std::string& text);
// A header by its lower-case name, "" when absent.
std::string header(const Request& r, const std::string& name);
// "h:1" -> "h", "[::1]:8080" -> "::1"
std::string host_name(const std::string& authority);
// False when Origin, Referer or Sec-Fetch-Site name another site.
bool same_origin(const Request& r);
bool equal_constant_time(const std::string& a, const std::string& b);
std::string cookie(const Request& r, const std::string& name);
std::string content_type_for(const std::string& name);
// A job report's headline figures (porosity, ink, time, layers, strands per layer).
nlohmann::json figures_of(const nlohmann::json& report);

struct Api::State {
  ApiOptions options;
  std::filesystem::path dir;
  Store store;
  // Sweeps still running: their progress (done, total, failed) by id, for GET /api/sweeps/{id}
  // (sweep_api.cpp). Declared before the pool, whose workers update it.
  std::mutex sweep_mu;
  std::map<std::int64_t, nlohmann::json> sweep_progress;
  WorkerPool pool;
  std::unique_ptr<Queue> queue;  // the machine queue and its sender threads (queue.h)

  State(const ApiOptions& o, const std::filesystem::path& d);
  ~State();  // stops the queue's senders first

  std::filesystem::path job_dir(std::int64_t id) const { return dir / "jobs" / std::to_string(id); }

  void drop_job(std::int64_t id) {
    store.remove(id);
    std::error_code ec;
    std::filesystem::remove_all(job_dir(id), ec);
  }

  // A new job's row (kept in the gallery when `save`) and its folder; HttpError 500 with
  // nothing left behind when the folder cannot be made.
  std::int64_t new_job(bool save, const std::string& name, const std::string& job) {
    const std::int64_t id = store.insert(save, name, job);
    std::error_code ec;
    std::filesystem::create_directories(job_dir(id), ec);
    if (ec) {
      drop_job(id);
      throw HttpError(500, "cannot create the job's directory (" + ec.message() + ")");
    }
    return id;
  }

  Response route(const Request& r);
  // GET /queue, /api/ports, /api/queue..., /api/events (queue_api.cpp).
  Response route_queue(const Request& r);
  // GET /draw and POST /api/plot (plot_api.cpp).
  Response route_plot(const Request& r);
  // GET /slice and POST /api/slice (slice_api.cpp).
  Response route_slice(const Request& r);
  // GET /sweep, POST /api/sweeps, GET /api/sweeps/{id}[/files/...] (sweep_api.cpp).
  Response route_sweeps(const Request& r);
  // GET /view/{id}, /assets/viewer.js, /api/jobs/{id}/view[/layers] (view_api.cpp).
  Response route_view(const Request& r);
  nlohmann::json sweep_state(const JobRow& row);
  nlohmann::json with_saved_job(nlohmann::json sweep);
  Response run(const Request& r, bool save);
  nlohmann::json produce(std::int64_t id, const jobs::JobSpec& spec, const std::string& ext);
  nlohmann::json summary_of(const JobRow& row, bool with_report);
};

}  // namespace strand::serve
