// The host side of streaming G-code, without any I/O: what to write next and what each reply
// means. Marlin and RepRapFirmware: one numbered, checksummed line in flight ("ok" sends the
// next; "Resend: N" rewinds to N; a silent firmware is probed with M105, never by sending a
// line twice). GRBL: character counting, as many lines in flight as fit its 127-byte receive
// buffer; a silent GRBL is asked for its status ('?'); idle means every line has run.
// Line numbers are the streamer's: M110 commands in the file are left out, a resend request
// for a line never sent stops the job, and so do endless resend requests.
#pragma once

#include <cstddef>
#include <deque>
#include <string>
#include <vector>

#include "machines/send/protocol.h"

namespace strand::machines {

// GRBL's serial receive buffer (128 bytes) less one, as its streaming guide counts.
inline constexpr std::size_t kGrblBufferBytes = 127;
// Marlin/RRF: resend requests in a row that bring no new line through before the job stops
// (a line the firmware can never accept would otherwise be sent for ever).
inline constexpr int kMaxResendsWithoutProgress = 25;

enum class StreamState {
  Running,
  Done,    // every command acknowledged
  Paused,  // pause() asked and nothing is in flight any more
  Failed,  // the firmware reported an error, an alarm or a restart
};

class Streamer {
 public:
  Streamer(Firmware firmware, std::vector<Command> commands);

  // Bytes to write now ("" while waiting for replies or when finished).
  std::string next_write();
  // One line received from the firmware.
  void on_line(std::string_view line);
  // Nothing received for the timeout: bytes that ask the firmware where it stands.
  std::string on_silence();
  // Stop sending new commands; Paused once the ones in flight are acknowledged.
  void pause();

  StreamState state() const { return state_; }
  std::size_t acknowledged() const { return acked_; }  // commands confirmed, in order
  std::size_t total() const { return commands_.size(); }
  // The file line to resume from: the first command not confirmed (after a failure, the
  // one the firmware failed on). 0 when done.
  int resume_line() const;
  const std::string& failure() const { return failure_; }  // the firmware's message
  // The last line received from the firmware, as received (for a monitor to show).
  const std::string& last_reply() const { return last_reply_; }

 private:
  bool numbered_protocol() const { return firmware_ != Firmware::Grbl; }
  void acknowledge_front();
  void fail(const std::string& message);
  void update_state();

  Firmware firmware_;
  std::vector<Command> commands_;
  StreamState state_ = StreamState::Running;
  std::string failure_;
  std::string last_reply_;
  std::size_t acked_ = 0;    // commands_[0, acked_) confirmed
  std::size_t sent_ = 0;     // commands_[0, sent_) written (Marlin: at most acked_ + 1)
  bool reset_sent_ = false;  // Marlin/RRF: "M110 N0" written
  bool reset_acked_ = false;
  bool ignore_ok_ = false;  // the "ok" that follows a resend request acknowledges nothing
  bool pausing_ = false;
  std::size_t best_acked_ = 0;  // the most commands ever confirmed (a rewind lowers acked_)
  int resends_without_progress_ = 0;
  std::deque<std::size_t> in_buffer_;  // GRBL: bytes of each line in flight
};

}  // namespace strand::machines
