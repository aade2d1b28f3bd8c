// Event backlog and listeners: each listener waits at most a second per call, so the HTTP
// thread serving it notices a stopping server and a closed connection promptly.
#include "serve/queue_events.h"

#include <chrono>
#include <memory>

namespace strand::serve {

// Holds a listener's place; released when the stream function is destroyed.
struct EventHub::Listener {
  EventHub* hub;
  std::uint64_t cursor;  // sequence number of the next event to send
  bool greeted = false;
  std::chrono::steady_clock::time_point last_write = std::chrono::steady_clock::now();
  ~Listener() {
    const std::lock_guard<std::mutex> lock(hub->mu_);
    --hub->clients_;
  }
};

void EventHub::publish(const std::string& event, const std::string& data) {
  {
    const std::lock_guard<std::mutex> lock(mu_);
    backlog_.push_back("event: " + event + "\ndata: " + data + "\n\n");
    ++next_seq_;
    if (backlog_.size() > kEventBacklog) backlog_.pop_front();
  }
  cv_.notify_all();
}

std::function<bool(std::string&)> EventHub::subscribe() {
  std::shared_ptr<Listener> l;
  {
    const std::lock_guard<std::mutex> lock(mu_);
    if (closed_ || clients_ >= kMaxEventClients) return {};
    ++clients_;
    l.reset(new Listener{this, next_seq_});  // in place: a temporary's destructor would count down
  }
  return [this, l](std::string& out) {
    using Clock = std::chrono::steady_clock;
    if (!l->greeted) {  // at once, so the client sees the stream open
      l->greeted = true;
      out = "retry: 2000\n: queue events\n\n";
      return true;
    }
    std::unique_lock<std::mutex> lock(mu_);
    cv_.wait_for(lock, std::chrono::seconds(1), [&] { return closed_ || next_seq_ > l->cursor; });
    if (closed_) return false;
    const std::uint64_t oldest = next_seq_ - backlog_.size();
    if (l->cursor < oldest) {  // fell behind the backlog: the page reloads the whole queue
      out = "event: reset\ndata: {}\n\n";
      l->cursor = oldest;
    }
    for (std::uint64_t s = l->cursor; s < next_seq_; ++s) out += backlog_[static_cast<std::size_t>(s - oldest)];
    l->cursor = next_seq_;
    const auto now = Clock::now();
    if (out.empty() && now - l->last_write >= std::chrono::milliseconds(kEventKeepAliveMs)) out = ": keep-alive\n\n";
    if (!out.empty()) l->last_write = now;
    return true;
  };
}

void EventHub::close() {
  {
    const std::lock_guard<std::mutex> lock(mu_);
    closed_ = true;
  }
  cv_.notify_all();
}

std::size_t EventHub::clients() {
  const std::lock_guard<std::mutex> lock(mu_);
  return clients_;
}

}  // namespace strand::serve
