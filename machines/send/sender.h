// Driving a Streamer over a serial port: write what it asks, feed it every reply, probe a
// silent firmware, honour a pause request between commands, and say how the run ended.
#pragma once

#include <atomic>
#include <functional>
#include <string>

#include "machines/send/serial_port.h"
#include "machines/send/streamer.h"

namespace strand::machines {

struct StreamOptions {
  int silence_ms = 5000;   // no reply for this long: probe the firmware (M105 or '?')
  int max_probes = 6;      // unanswered probes in a row before giving up
};

enum class StreamEnd {
  Done,
  Failed,        // firmware error, alarm or restart: message + the line it failed on
  Paused,        // pause requested; everything sent was acknowledged
  Disconnected,  // the port went away
  NoReply,       // the firmware stopped answering
};

struct StreamResult {
  StreamEnd end = StreamEnd::Done;
  int resume_line = 0;     // file line to resume from (0 when done)
  std::string message;
};

using ProgressFn = std::function<void(const Streamer&)>;

StreamResult stream(SerialPort& port, Streamer& s, const StreamOptions& o,
                    const std::atomic<bool>& pause_requested, const ProgressFn& progress);

}  // namespace strand::machines
