// What the queue keeps in memory only, shared by queue.cpp (actions) and queue_run.cpp (the
// sender threads); guarded by Queue's mutex except where noted.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <deque>
#include <string>
#include <thread>

#include "serve/queue.h"

namespace strand::serve {

// Per entry: what the page shows beyond its row.
struct Queue::Live {
  std::deque<std::string> messages;  // the newest kKeptFirmwareMessages firmware lines
  double time_left_s = -1.0;         // from the file's moves; < 0: unknown
  bool pause = false;                // asked to pause
  bool cancel = false;               // asked to cancel
  bool homing = false;               // "home" running on its port
  std::chrono::steady_clock::time_point last_event{};
};

// Per serial device: the one sender thread that may use it.
struct Queue::Port {
  std::thread thread;
  std::atomic<bool> pause{false};  // read by the sender without the mutex
  std::int64_t entry = 0;          // the entry it runs
  bool busy = false;               // a run is under way (cleared as its thread's last act)
};

}  // namespace strand::serve
