// The send loop: writes, reads with short slices (so a pause request is seen quickly),
// probes after o.silence_ms of silence.
#include "machines/send/sender.h"

#include <algorithm>

namespace strand::machines {

namespace {

// Reads wait at most this long so a pause request is noticed promptly, ms.
constexpr int kReadSliceMs = 100;

}  // namespace

StreamResult stream(SerialPort& port, Streamer& s, const StreamOptions& o,
                    const std::atomic<bool>& pause_requested, const ProgressFn& progress) {
  int silent_ms = 0, probes = 0;
  try {
    while (s.state() == StreamState::Running) {
      if (pause_requested.load()) s.pause();
      const std::string out = s.next_write();
      if (!out.empty()) port.write_all(out);
      if (s.state() != StreamState::Running) break;
      const auto line = port.read_line(std::min(kReadSliceMs, o.silence_ms));
      if (line) {
        s.on_line(*line);
        silent_ms = 0;
        probes = 0;
        if (progress) progress(s);
        continue;
      }
      silent_ms += std::min(kReadSliceMs, o.silence_ms);
      if (silent_ms < o.silence_ms) continue;
      silent_ms = 0;
      if (++probes > o.max_probes) {
        return {StreamEnd::NoReply, s.resume_line(), "no reply from the firmware for " +
                std::to_string(o.silence_ms * (o.max_probes + 1) / 1000) + " s"};
      }
      const std::string probe = s.on_silence();
      if (!probe.empty()) port.write_all(probe);
    }
  } catch (const Disconnected& e) {
    return {StreamEnd::Disconnected, s.resume_line(), e.what()};
  }
  switch (s.state()) {
    case StreamState::Done: return {StreamEnd::Done, 0, ""};
    case StreamState::Paused: return {StreamEnd::Paused, s.resume_line(), ""};
    case StreamState::Failed: return {StreamEnd::Failed, s.resume_line(), s.failure()};
    case StreamState::Running: break;
  }
  return {StreamEnd::Failed, s.resume_line(), "stopped"};
}

}  // namespace strand::machines
