// `strand send FILE.gcode --port DEV`: streams a file to a Marlin, RepRapFirmware or GRBL
// controller with a progress bar; Ctrl-C, SIGTERM and SIGHUP pause cleanly (the profile's
// pen up / valve closed, sent even to a silent firmware), a firmware error or a lost port
// stops with the line to resume from, and `--resume-from LINE` restores the modal state
// before going on.
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <csignal>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>

#include "cli/commands.h"
#include "cli/progress_bar.h"
#include "jobs/send_estimate.h"
#include "machines/gcode_format.h"
#include "machines/send/resume.h"
#include "machines/send/sender.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"

namespace strand::cli {

using jobs::time_left_after;
using jobs::time_left_at;

namespace {

std::atomic<bool> g_pause{false};
extern "C" void on_interrupt(int) { g_pause.store(true); }

struct SendArgs {
  std::string file, port, machine, firmware;
  int baud = 115200;
  int resume_from = 0;
  double timeout_s = 5.0;
};

machines::Firmware firmware_of(const SendArgs& a, const machines::MachineProfile* m) {
  const std::map<std::string, machines::Firmware> kNames = {
      {"marlin", machines::Firmware::Marlin},
      {"reprap", machines::Firmware::RepRap},
      {"klipper", machines::Firmware::Klipper},
      {"grbl", machines::Firmware::Grbl}};
  if (!a.firmware.empty()) {
    if (!kNames.count(a.firmware))
      throw InputError("send.firmware = " + a.firmware +
                       ": must be one of marlin, reprap, klipper, grbl");
    return kNames.at(a.firmware);
  }
  return m ? m->firmware : machines::Firmware::Marlin;
}

std::string hms_text(double s) {
  const long v = static_cast<long>(s + 0.5);
  return std::to_string(v / 3600) + "h" + (v / 60 % 60 < 10 ? "0" : "") +
         std::to_string(v / 60 % 60) + "m" + (v % 60 < 10 ? "0" : "") + std::to_string(v % 60) +
         "s";
}

void draw_progress(const machines::Streamer& s, const std::vector<machines::Command>& cmds,
                   const std::map<int, double>& left) {
  const double f = s.total() ? static_cast<double>(s.acknowledged()) / s.total() : 1.0;
  const int line = s.acknowledged() > 0 ? cmds[s.acknowledged() - 1].file_line : 0;
  const double rest = time_left_at(left, line);
  const int bar = static_cast<int>(f * 30);
  std::cerr << "\r[" << std::string(bar, '#') << std::string(30 - bar, ' ') << "] "
            << machines::fmt_fixed(100 * f, 0) << "% line " << line << ", " << hms_text(rest)
            << " left " << std::flush;
}

// Runs extra commands (preamble, safe state) to completion; false if that failed.
bool run_extra(machines::SerialPort& port, machines::Firmware fw,
               const std::vector<std::string>& lines, const machines::StreamOptions& o) {
  std::vector<machines::Command> cmds;
  for (const auto& l : lines) {
    std::string c = l.substr(0, l.find(';'));
    while (!c.empty() && c.back() == ' ') c.pop_back();
    cmds.push_back({0, c});
  }
  machines::Streamer s(fw, cmds);
  const std::atomic<bool> never{false};
  return machines::stream(port, s, o, never, nullptr).end == machines::StreamEnd::Done;
}

// What the end of a run means for the user: the summary, or the pause / stop with the line
// to resume from; after a pause the machine is first made safe.
int finish(const SendArgs& a, const machines::StreamResult& r, const machines::Streamer& s,
           const std::vector<machines::Command>& all, const machines::MachineProfile* m,
           machines::SerialPort& port, machines::Firmware fw, const machines::StreamOptions& o) {
  const std::string resume = "resume with: strand send " + a.file + " --port " + a.port +
                             " --resume-from " + std::to_string(r.resume_line);
  switch (r.end) {
    case machines::StreamEnd::Done:
      std::cout << "  sent           " << s.total() << " commands\n";
      return 0;
    case machines::StreamEnd::Paused: {
      const auto safe =
          m ? machines::safe_state_gcode(*m, machines::modal_state_before(all, r.resume_line, *m))
            : std::vector<std::string>{};
      // the firmware may be silent: plain lines, each with a bounded wait, none held back
      const std::size_t confirmed = machines::send_unnumbered(port, fw, safe, o.silence_ms);
      std::cout << "  paused         before line " << r.resume_line
                << (safe.empty() ? "" : " (" + safe.front() + ")") << "; " << resume << "\n";
      if (r.unconfirmed) {
        std::cout << "  unconfirmed    the firmware did not confirm line " << r.resume_line
                  << " (it fell silent): it may have run; check the machine before resuming\n";
      }
      if (confirmed < safe.size()) {
        std::cout << "  unconfirmed    the safe-state lines were sent, " << confirmed << " of "
                  << safe.size() << " confirmed: check the machine\n";
      }
      return 130;
    }
    case machines::StreamEnd::Failed:
      std::cerr << "strand: firmware error at line " << r.resume_line << ": " << r.message << "; "
                << resume << "\n";
      return 1;
    case machines::StreamEnd::Disconnected:
    case machines::StreamEnd::NoReply:
      std::cerr << "strand: stopped at line " << r.resume_line << ": " << r.message << "; "
                << resume << "\n";
      return 1;
  }
  return 1;
}

// The file's own M110 lines are not sent (Strand numbers the lines); say which.
void note_line_number_resets(const std::vector<machines::Command>& all) {
  constexpr int kShown = 5;
  int n = 0;
  for (const auto& c : all) {
    if (!machines::sets_line_number(c.text)) continue;
    if (++n <= kShown) {
      std::cout << "  note           line " << c.file_line << ": " << c.text
                << " is not sent (Strand numbers the lines itself)\n";
    }
  }
  if (n > kShown)
    std::cout << "  note           " << n - kShown << " more M110 lines are not sent\n";
}

int run_send(const SendArgs& a) {
  if (!std::isfinite(a.timeout_s) || a.timeout_s < 0.05 || a.timeout_s > 600.0) {
    std::ostringstream shown;
    shown << a.timeout_s;
    throw InputError("--timeout = " + shown.str() + ": must be a number of seconds in [0.05, 600]");
  }
  const std::string text = slicer::read_file(a.file);
  const std::vector<machines::Command> all = machines::commands_of(text, a.file);
  std::unique_ptr<machines::MachineProfile> m;
  if (!a.machine.empty())
    m = std::make_unique<machines::MachineProfile>(machines::load_profile(a.machine));
  const machines::Firmware fw = firmware_of(a, m.get());
  if (fw == machines::Firmware::Grbl) machines::refuse_grbl_realtime_characters(all, a.file);
  std::vector<machines::Command> cmds = all;
  std::erase_if(cmds,
                [](const machines::Command& c) { return machines::sets_line_number(c.text); });
  if (cmds.empty())
    throw InputError(a.file + ": no G-code commands to send (its only commands are M110)");
  std::vector<std::string> preamble;
  if (a.resume_from != 0) {
    if (a.resume_from < 1 || a.resume_from > all.back().file_line) {
      throw InputError("send.resume-from = " + std::to_string(a.resume_from) + ": must be in [1, " +
                       std::to_string(all.back().file_line) + "] (a line of " + a.file + ")");
    }
    std::erase_if(cmds, [&](const machines::Command& c) { return c.file_line < a.resume_from; });
    const machines::MachineProfile none;
    preamble = machines::resume_preamble(
        m ? *m : none, machines::modal_state_before(all, a.resume_from, m ? *m : none));
  }
  const std::map<int, double> left = time_left_after(text);
  machines::SerialPort port(a.port, a.baud);
  machines::StreamOptions o;
  o.silence_ms = static_cast<int>(a.timeout_s * 1000);
  struct sigaction sa {};
  sa.sa_handler = on_interrupt;  // no SA_RESTART: a blocked read returns at once
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) sigaction(sig, &sa, nullptr);
  std::cout << "send " << a.file << " -> " << a.port << " (" << machines::to_string(fw) << ", "
            << a.baud << " baud, " << cmds.size() << " commands"
            << (a.resume_from ? ", resuming at line " + std::to_string(a.resume_from) : "")
            << ")\n";
  note_line_number_resets(all);
  std::cout << std::flush;
  if (!preamble.empty() && !run_extra(port, fw, preamble, o))
    throw InputError("send: the controller refused the resume preamble");
  machines::Streamer s(fw, cmds);
  const bool tty = isatty(STDERR_FILENO) && progress_mode() != ProgressMode::Quiet;
  const auto progress = [&](const machines::Streamer& st) {
    if (tty) draw_progress(st, cmds, left);
  };
  const machines::StreamResult r = machines::stream(port, s, o, g_pause, progress);
  if (tty) std::cerr << "\n";
  return finish(a, r, s, all, m.get(), port, fw, o);
}

}  // namespace

void add_send_command(CLI::App& app, Action& action) {
  auto a = std::make_shared<SendArgs>();
  CLI::App* sub = app.add_subcommand(
      "send",
      "stream a G-code file to a Marlin, RepRapFirmware or GRBL controller over a serial port");
  sub->add_option("file", a->file, "G-code file")->required();
  sub->add_option("--port", a->port, "serial device, e.g. /dev/ttyUSB0 or /dev/ttyACM0")
      ->required();
  sub->add_option("--baud", a->baud, "baud rate (default 115200)");
  sub->add_option("--machine", a->machine,
                  "machine profile: its firmware, and its pen up / valve close for a clean pause");
  sub->add_option("--firmware", a->firmware,
                  "marlin, reprap, klipper or grbl (default: the machine's, else marlin)");
  sub->add_option("--resume-from", a->resume_from,
                  "file line to start at after a stop; the modal state before it is sent first");
  sub->add_option(
      "--timeout", a->timeout_s,
      "seconds of silence before the firmware is asked where it stands, 0.05 to 600 (default 5)");
  sub->callback([&action, a] { action = [a] { return run_send(*a); }; });
}

}  // namespace strand::cli
