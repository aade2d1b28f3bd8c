// Server-Sent Events for the queue page: a bounded backlog of events and a bounded number of
// listeners, each reading the backlog from where it joined (GET /api/events).
#pragma once

#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <mutex>
#include <string>

namespace strand::serve {

// Listeners at once; more are refused (503) so they cannot hold every HTTP thread.
inline constexpr std::size_t kMaxEventClients = 4;
// Events kept for listeners that fall behind; one further behind is told to reload ("reset").
inline constexpr std::size_t kEventBacklog = 512;
// A listener that has had nothing for this long gets a comment line, which finds a closed
// connection (and frees its place), ms.
inline constexpr int kEventKeepAliveMs = 5000;

class EventHub {
 public:
  EventHub() = default;
  EventHub(const EventHub&) = delete;
  EventHub& operator=(const EventHub&) = delete;

  // `data` is one line (compact JSON).
  void publish(const std::string& event, const std::string& data);
  // A Response::stream for a new listener, or an empty function when kMaxEventClients listen.
  std::function<bool(std::string&)> subscribe();
  // Ends every stream (the server is stopping).
  void close();
  std::size_t clients();

 private:
  struct Listener;
  std::mutex mu_;
  std::condition_variable cv_;
  std::deque<std::string> backlog_;  // formatted events, the newest last
  std::uint64_t next_seq_ = 0;       // sequence number of the next event
  std::size_t clients_ = 0;
  bool closed_ = false;
};

}  // namespace strand::serve
