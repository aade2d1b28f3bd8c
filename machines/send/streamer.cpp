// Streaming state machine for Marlin/RepRapFirmware (ping-pong with line numbers) and GRBL
// (character counting).
#include "machines/send/streamer.h"

#include <numeric>

namespace strand::machines {

Streamer::Streamer(Firmware firmware, std::vector<Command> commands)
    : firmware_(firmware), commands_(std::move(commands)) {
  // the numbering is Strand's: a file's own M110 would make the firmware replay or skip lines
  std::erase_if(commands_, [](const Command& c) { return sets_line_number(c.text); });
  update_state();
}

std::string Streamer::next_write() {
  if (state_ != StreamState::Running || pausing_) return "";
  if (numbered_protocol()) {
    if (!reset_sent_) {
      reset_sent_ = true;  // line numbers restart at 1 with the first command
      return "M110 N0\n";
    }
    if (!reset_acked_ || ignore_ok_ || sent_ > acked_ || sent_ >= commands_.size()) return "";
    ++sent_;
    return numbered(static_cast<long>(sent_), commands_[sent_ - 1].text) + "\n";
  }
  std::string out;
  std::size_t used = std::accumulate(in_buffer_.begin(), in_buffer_.end(), std::size_t{0});
  while (sent_ < commands_.size()) {
    const std::size_t bytes = commands_[sent_].text.size() + 1;
    // a line longer than the buffer is sent alone, once the buffer is empty
    if (used + bytes > kGrblBufferBytes && !in_buffer_.empty()) break;
    out += commands_[sent_].text + "\n";
    in_buffer_.push_back(bytes);
    used += bytes;
    ++sent_;
  }
  return out;
}

void Streamer::acknowledge_front() {
  if (numbered_protocol()) {
    if (!reset_acked_) {
      reset_acked_ = true;
    } else if (sent_ > acked_) {
      acked_ = sent_;
    }
  } else if (!in_buffer_.empty()) {
    in_buffer_.pop_front();
    ++acked_;
  }
  if (acked_ > best_acked_) {
    best_acked_ = acked_;
    resends_without_progress_ = 0;
  }
  update_state();
}

void Streamer::on_line(std::string_view line) {
  if (state_ == StreamState::Failed || state_ == StreamState::Done) return;
  last_reply_.assign(line);
  const Reply r = parse_reply(line, firmware_);
  switch (r.kind) {
    case ReplyKind::Ok:
      if (ignore_ok_) {
        ignore_ok_ = false;
      } else {
        acknowledge_front();
      }
      break;
    case ReplyKind::Resend:
      if (numbered_protocol() && !reset_acked_) {
        reset_sent_ = false;  // the line-number reset itself was garbled
        ignore_ok_ = true;
      } else if (numbered_protocol() &&
                 (r.line < 1 || static_cast<std::size_t>(r.line) > sent_ + 1)) {
        // a line never sent: the firmware's numbering is no longer Strand's, and taking the
        // next "ok" as an acknowledgement would skip commands
        fail("the firmware asked for line " + std::to_string(r.line) + ", but only " +
             std::to_string(sent_) + " were sent (" + r.text + ")");
      } else if (numbered_protocol() && ++resends_without_progress_ > kMaxResendsWithoutProgress) {
        fail("the firmware asked to resend " + std::to_string(kMaxResendsWithoutProgress) +
             " times without getting further (" + r.text + ")");
      } else if (numbered_protocol()) {
        // lines before the one asked for have all arrived and the rest has not: rewind to it
        // (this also corrects an M105 probe that answered for a line which was lost)
        acked_ = static_cast<std::size_t>(r.line) - 1;
        sent_ = acked_;
        ignore_ok_ = true;
      }
      break;
    case ReplyKind::Error:
    case ReplyKind::Alarm:
      fail(r.text);
      break;
    case ReplyKind::Restart:
      if (sent_ > 0) fail("the controller restarted (" + r.text + ")");
      break;
    case ReplyKind::Status:
      // asked after a silence: an idle GRBL has run every line it was sent
      if (r.idle) {
        while (!in_buffer_.empty()) acknowledge_front();
      }
      break;
    case ReplyKind::Busy:
    case ReplyKind::LineError:
    case ReplyKind::Other:
      break;
  }
  update_state();
}

std::string Streamer::on_silence() {
  if (state_ != StreamState::Running) return "";
  if (!numbered_protocol()) return in_buffer_.empty() ? "" : "?";
  if (!reset_sent_ || (!reset_acked_ && !ignore_ok_)) {
    reset_sent_ = false;  // the reset may have been lost while the board was starting
    return next_write();
  }
  // M105 runs after whatever is in flight, so its "ok" proves that line has run; a line
  // that never arrived is caught by the line number of the next one (a resend request).
  if (sent_ > acked_ || ignore_ok_) {
    ignore_ok_ = false;
    return "M105\n";
  }
  return "";
}

void Streamer::pause() {
  pausing_ = true;
  update_state();
}

int Streamer::resume_line() const {
  return acked_ < commands_.size() ? commands_[acked_].file_line : 0;
}

void Streamer::fail(const std::string& message) {
  state_ = StreamState::Failed;
  failure_ = message;
}

void Streamer::update_state() {
  if (state_ == StreamState::Failed) return;
  const bool in_flight = numbered_protocol() ? sent_ > acked_ : !in_buffer_.empty();
  if (acked_ == commands_.size()) {
    state_ = StreamState::Done;
  } else if (pausing_ && !in_flight) {
    state_ = StreamState::Paused;
  } else {
    state_ = StreamState::Running;
  }
}

}  // namespace strand::machines
