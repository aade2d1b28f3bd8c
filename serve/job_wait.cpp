// Running a request's job on the pool and waiting for it (see job_wait.h).
#include "serve/job_wait.h"

#include <chrono>
#include <future>
#include <memory>
#include <string>

#include "serve/api.h"
#include "serve/api_state.h"
#include "slicer/input_error.h"

namespace strand::serve {

using nlohmann::json;

json run_and_wait(WorkerPool& pool, std::int64_t id, const std::function<void()>& drop,
                  std::function<json()> work) {
  auto promise = std::make_shared<std::promise<json>>();
  std::future<json> done = promise->get_future();
  const bool queued = pool.submit([work = std::move(work), promise] {
    try {
      promise->set_value(work());
    } catch (...) {
      promise->set_exception(std::current_exception());
    }
  });
  if (!queued) {
    drop();
    throw HttpError(503, "the server is busy (" + std::to_string(kMaxWaitingJobs) +
                             " jobs waiting); try again");
  }
  if (done.wait_for(std::chrono::seconds(kMaxJobWaitSeconds)) != std::future_status::ready) {
    throw HttpError(503, "job " + std::to_string(id) + " takes longer than " +
                             std::to_string(kMaxJobWaitSeconds) + " s; see GET /api/jobs/" +
                             std::to_string(id));
  }
  try {
    return done.get();
  } catch (const InputError&) {
    drop();
    throw;
  } catch (const std::exception& e) {
    drop();
    throw HttpError(500, std::string("internal error: ") + e.what());
  }
}

}  // namespace strand::serve
