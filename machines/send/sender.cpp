// The send loop: writes, reads with short slices (so a stop request is seen quickly),
// probes after o.silence_ms of silence; once a stop is requested, bounded waits only.
#include "machines/send/sender.h"

#include <algorithm>
#include <chrono>

namespace strand::machines {

namespace {

// Reads wait at most this long so a stop request is noticed promptly, ms.
constexpr int kReadSliceMs = 100;

using Clock = std::chrono::steady_clock;

long ms_since(Clock::time_point t) {
  return static_cast<long>(
      std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - t).count());
}

}  // namespace

StreamResult stream(SerialPort& port, Streamer& s, const StreamOptions& o,
                    const std::atomic<bool>& pause_requested, const ProgressFn& progress) {
  int silent_ms = 0, probes = 0;
  bool stopping = false;
  Clock::time_point stop_at;
  const int slice = std::min(kReadSliceMs, o.silence_ms);
  try {
    while (s.state() == StreamState::Running) {
      if (pause_requested.load() && !stopping) {
        s.pause();
        stopping = true;
        stop_at = Clock::now();
        probes = 0;  // the stop gets its own bounded wait: one probe, then give up
      }
      if (stopping && ms_since(stop_at) >= o.stop_wait_max_ms) break;
      const std::string out = s.next_write();
      if (!out.empty()) port.write_all(out);
      if (s.state() != StreamState::Running) break;
      const auto line = port.read_line(slice);
      if (line) {
        s.on_line(*line);
        silent_ms = 0;
        probes = 0;
        if (progress) progress(s);
        continue;
      }
      silent_ms += slice;
      if (silent_ms < o.silence_ms) continue;
      silent_ms = 0;
      if (stopping && ++probes > 1) break;
      if (!stopping && ++probes > o.max_probes) {
        return {StreamEnd::NoReply, s.resume_line(),
                "no reply from the firmware for " +
                    std::to_string(o.silence_ms * (o.max_probes + 1) / 1000) + " s",
                false};
      }
      const std::string probe = s.on_silence();
      if (!probe.empty()) port.write_all(probe);
    }
  } catch (const Disconnected& e) {
    return {StreamEnd::Disconnected, s.resume_line(), e.what(), false};
  }
  switch (s.state()) {
    case StreamState::Done:
      return {StreamEnd::Done, 0, "", false};
    case StreamState::Paused:
      return {StreamEnd::Paused, s.resume_line(), "", false};
    case StreamState::Failed:
      return {StreamEnd::Failed, s.resume_line(), s.failure(), false};
    case StreamState::Running:
      break;
  }
  if (stopping)
    return {StreamEnd::Paused, s.resume_line(), "the firmware did not confirm the lines in flight",
            true};
  return {StreamEnd::Failed, s.resume_line(), "stopped", false};
}

std::size_t send_unnumbered(SerialPort& port, Firmware firmware,
                            const std::vector<std::string>& lines, int wait_ms) {
  std::size_t confirmed = 0;
  try {
    for (const auto& l : lines) {
      std::string c = l.substr(0, l.find(';'));
      while (!c.empty() && c.back() == ' ') c.pop_back();
      if (c.empty()) continue;
      port.write_all(c + "\n");
      const auto sent_at = Clock::now();
      while (ms_since(sent_at) < wait_ms) {
        const auto reply =
            port.read_line(static_cast<int>(std::max(1L, wait_ms - ms_since(sent_at))));
        if (!reply) continue;
        const ReplyKind k = parse_reply(*reply, firmware).kind;
        if (k == ReplyKind::Ok) {
          ++confirmed;
          break;
        }
        if (k == ReplyKind::Error || k == ReplyKind::Alarm) break;
      }
    }
  } catch (const Disconnected&) {
  }
  return confirmed;
}

}  // namespace strand::machines
