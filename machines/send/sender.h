// Driving a Streamer over a serial port: write what it asks, feed it every reply, probe a
// silent firmware, honour a stop request between commands (waiting a bounded time for the
// lines in flight), say how the run ended, and send a few safe-state lines to a firmware
// that may not answer.
#pragma once

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "machines/send/serial_port.h"
#include "machines/send/streamer.h"

namespace strand::machines {

struct StreamOptions {
  int silence_ms = 5000;  // no reply for this long: probe the firmware (M105 or '?')
  int max_probes = 6;     // unanswered probes in a row before giving up
  // After a stop request the lines in flight get this long in all (a firmware that keeps
  // saying "busy:" while heating could otherwise hold the stop for minutes), and one probe
  // after silence_ms of silence; then the run ends Paused with them unconfirmed.
  int stop_wait_max_ms = 30000;
};

enum class StreamEnd {
  Done,
  Failed,        // firmware error, alarm or restart: message + the line it failed on
  Paused,        // stop requested; see StreamResult::unconfirmed
  Disconnected,  // the port went away
  NoReply,       // the firmware stopped answering
};

struct StreamResult {
  StreamEnd end = StreamEnd::Done;
  int resume_line = 0;  // file line to resume from (0 when done)
  std::string message;
  bool unconfirmed = false;  // Paused: lines were in flight and the firmware never confirmed
                             // them (it fell silent): resume_line may already have run
};

using ProgressFn = std::function<void(const Streamer&)>;

StreamResult stream(SerialPort& port, Streamer& s, const StreamOptions& o,
                    const std::atomic<bool>& pause_requested, const ProgressFn& progress);

// Sends `lines` without line numbers (Marlin, RepRapFirmware and Klipper accept plain lines
// whatever the numbering state; GRBL has none), each followed by a wait of at most wait_ms
// for its "ok"; a line that is not confirmed does not hold back the next. Comments are
// stripped. Returns how many lines were confirmed; never throws Disconnected.
std::size_t send_unnumbered(SerialPort& port, Firmware firmware,
                            const std::vector<std::string>& lines, int wait_ms);

}  // namespace strand::machines
