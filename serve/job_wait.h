// A request's job run on the worker pool and waited for, as POST /api/generate waits: at most
// kMaxJobWaitSeconds (then 503; the job still finishes), 503 when the queue is full.
#pragma once

#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>

#include "serve/worker_pool.h"

namespace strand::serve {

// Runs `work` on `pool` and returns its result. `drop` removes job `id` when the work fails
// or cannot be queued; an InputError from `work` is rethrown (a 400), others become a 500.
nlohmann::json run_and_wait(WorkerPool& pool, std::int64_t id, const std::function<void()>& drop,
                            std::function<nlohmann::json()> work);

}  // namespace strand::serve
