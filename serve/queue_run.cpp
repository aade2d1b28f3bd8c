// One run on a sender thread: the file's commands from the resume line (after the resume
// preamble, as `strand send --resume-from` sends it), progress written on every
// acknowledgement, and the stop recorded with the line to resume from. "home" sends the
// profile's safe state and a homing move instead.
#include <chrono>
#include <map>

#include "jobs/send_estimate.h"
#include "machines/profile.h"
#include "machines/send/resume.h"
#include "machines/send/sender.h"
#include "serve/queue_live.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"

namespace strand::serve {

namespace {

machines::Firmware firmware_named(const std::string& name) {
  if (name == "reprap") return machines::Firmware::RepRap;
  if (name == "klipper") return machines::Firmware::Klipper;
  if (name == "grbl") return machines::Firmware::Grbl;
  return machines::Firmware::Marlin;
}

machines::Command command_of(const std::string& line) { return {0, line.substr(0, line.find(';'))}; }

// Extra lines (resume preamble, homing) through a streamer of their own; true when all ran.
bool run_extra(machines::SerialPort& port, machines::Firmware fw, const std::vector<std::string>& lines,
               const machines::StreamOptions& o) {
  std::vector<machines::Command> cmds;
  for (const auto& l : lines) cmds.push_back(command_of(l));
  if (cmds.empty()) return true;
  machines::Streamer s(fw, cmds);
  const std::atomic<bool> never{false};
  return machines::stream(port, s, o, never, nullptr).end == machines::StreamEnd::Done;
}

machines::StreamOptions stream_options() {
  machines::StreamOptions o;
  o.stop_wait_max_ms = 3000;  // a pause, cancel or server stop waits this long for lines in flight
  return o;
}

// Waits for the firmware's reply to each safe-state line, ms.
constexpr int kSafeStateWaitMs = 1000;

}  // namespace

void Queue::run(std::int64_t id, const std::string& kind, Port* port) {
  QueueRow r;
  {
    const std::lock_guard<std::mutex> lock(mu_);
    r = rows_.at(id);
  }
  const machines::Firmware fw = firmware_named(r.firmware);
  machines::MachineProfile profile;
  try {
    profile = machines::load_profile(r.machine);
  } catch (const std::exception&) {  // a profile removed since: no safe state, no lift
  }
  profile.firmware = fw;
  const machines::StreamOptions o = stream_options();
  std::string outcome_state, message;
  int resume_line = r.resume_line, line = r.line;
  std::int64_t acked = r.acked, total = r.total;
  std::deque<std::string> firmware_lines;
  try {
    if (kind == "home") {
      machines::SerialPort serial(r.port, r.baud);
      std::vector<std::string> lines = machines::safe_state_gcode(profile, machines::ModalState{});
      if (fw == machines::Firmware::Grbl) {
        lines.insert(lines.end(), {"G90", "G0 X0 Y0"});
      } else {
        lines.push_back("G28");
      }
      message = run_extra(serial, fw, lines, o) ? "returned home" : "the controller did not confirm the return home";
    } else {
      const std::string text = slicer::read_file((dir_ / "jobs" / std::to_string(r.job) / r.file).string());
      const std::vector<machines::Command> all = machines::commands_of(text, r.file);
      if (fw == machines::Firmware::Grbl) machines::refuse_grbl_realtime_characters(all, r.file);
      std::vector<machines::Command> cmds = all;
      std::erase_if(cmds, [](const machines::Command& c) { return machines::sets_line_number(c.text); });
      total = static_cast<std::int64_t>(cmds.size());
      std::vector<std::string> preamble;
      if (resume_line > 0) {
        std::erase_if(cmds, [&](const machines::Command& c) { return c.file_line < resume_line; });
        preamble = machines::resume_preamble(profile, machines::modal_state_before(all, resume_line, profile));
      }
      const std::int64_t before = total - static_cast<std::int64_t>(cmds.size());
      acked = before;
      const std::map<int, double> left = jobs::time_left_after(text);
      machines::SerialPort serial(r.port, r.baud);
      {
        const std::lock_guard<std::mutex> lock(mu_);
        QueueRow& row = rows_.at(id);
        row.total = total;
        row.acked = acked;
        store_.update(row);
        live_.at(id)->time_left_s = jobs::time_left_at(left, line);
      }
      publish(id, false);
      if (!run_extra(serial, fw, preamble, o)) throw InputError("the controller refused the resume preamble");
      machines::Streamer s(fw, cmds);
      const auto progress = [&](const machines::Streamer& st) {
        const std::int64_t now_acked = before + static_cast<std::int64_t>(st.acknowledged());
        const bool moved = now_acked != acked;
        if (moved) {
          acked = now_acked;
          line = cmds[st.acknowledged() - 1].file_line;
          resume_line = st.resume_line();
          store_.progress(id, line, resume_line, acked);
        }
        const machines::Reply reply = machines::parse_reply(st.last_reply(), fw);
        const bool note = reply.kind != machines::ReplyKind::Ok && !reply.text.empty();
        if (!moved && !note) return;
        {
          const std::lock_guard<std::mutex> lock(mu_);
          QueueRow& row = rows_.at(id);
          row.line = line;
          row.resume_line = resume_line;
          row.acked = acked;
          Live& l = *live_.at(id);
          l.time_left_s = jobs::time_left_at(left, line);
          if (note) {
            l.messages.push_back(reply.text.substr(0, 200));
            if (l.messages.size() > kKeptFirmwareMessages) l.messages.pop_front();
          }
        }
        publish(id, !note);
      };
      const machines::StreamResult res = machines::stream(serial, s, o, port->pause, progress);
      resume_line = res.resume_line;
      acked = before + static_cast<std::int64_t>(s.acknowledged());
      switch (res.end) {
        case machines::StreamEnd::Done:
          outcome_state = "done";
          message = "sent " + std::to_string(total) + " commands";
          break;
        case machines::StreamEnd::Paused: {
          const auto safe = machines::safe_state_gcode(profile, machines::modal_state_before(all, resume_line, profile));
          const std::size_t confirmed = machines::send_unnumbered(serial, fw, safe, kSafeStateWaitMs);
          bool cancel = false, stopping = false;
          {
            const std::lock_guard<std::mutex> lock(mu_);
            cancel = live_.at(id)->cancel;
            stopping = stopping_;
          }
          outcome_state = cancel ? "cancelled" : stopping ? "interrupted" : "paused";
          message = cancel     ? "cancelled before line " + std::to_string(resume_line)
                    : stopping ? "the server stopped; resume from line " + std::to_string(resume_line)
                               : "paused before line " + std::to_string(resume_line);
          if (res.unconfirmed) message += "; the firmware did not confirm the line in flight: check the machine";
          if (confirmed < safe.size()) message += "; safe-state lines unconfirmed: check the machine";
          break;
        }
        case machines::StreamEnd::Failed:
          outcome_state = "failed";
          message = "firmware error at line " + std::to_string(resume_line) + ": " + res.message;
          break;
        case machines::StreamEnd::Disconnected:
        case machines::StreamEnd::NoReply:
          outcome_state = "failed";
          message = "stopped at line " + std::to_string(resume_line) + ": " + res.message;
          break;
      }
    }
  } catch (const std::exception& e) {
    outcome_state = kind == "home" ? "" : "failed";
    message = e.what();
  }
  {
    const std::lock_guard<std::mutex> lock(mu_);
    QueueRow& row = rows_.at(id);
    Live& l = *live_.at(id);
    if (kind == "home") {
      l.homing = false;
      l.messages.push_back(message.substr(0, 200));
      if (l.messages.size() > kKeptFirmwareMessages) l.messages.pop_front();
    } else {
      row.state = outcome_state;
      row.message = message.substr(0, 1000);
      row.total = total;
      row.acked = outcome_state == "done" ? total : acked;
      row.line = line;
      row.resume_line = outcome_state == "done" ? 0 : resume_line;
      l.pause = l.cancel = false;
      if (outcome_state == "done") l.time_left_s = 0.0;
      try {
        store_.update(row);
      } catch (const std::exception&) {  // the row keeps its last progress and comes back interrupted
      }
    }
  }
  publish(id, false);
  const std::lock_guard<std::mutex> lock(mu_);
  port->busy = false;
}

}  // namespace strand::serve
