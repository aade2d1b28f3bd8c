// The simulated controller's loop: a thread polls the pty master, answers like the
// firmware would and keeps the record the send tests compare with the file.
#include "tests/support/firmware_sim.h"

#include <fcntl.h>
#include <poll.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>

#include "machines/send/protocol.h"

namespace strand::testing {

FirmwareSim::FirmwareSim(bool grbl, SimFaults faults) : grbl_(grbl), f_(faults) {
  char name[128];
  termios raw{};
  cfmakeraw(&raw);
  if (openpty(&master_, &slave_, name, &raw, nullptr) != 0) std::abort();
  port_ = name;
  fcntl(master_, F_SETFL, O_NONBLOCK);
  thread_ = std::thread([this] { run(); });
}

FirmwareSim::~FirmwareSim() {
  stop_ = true;
  thread_.join();
  if (master_ >= 0) close(master_);
  if (slave_ >= 0) close(slave_);
}

std::vector<std::string> FirmwareSim::executed() const {
  std::lock_guard<std::mutex> l(mu_);
  return executed_;
}

std::vector<std::string> FirmwareSim::received() const {
  std::lock_guard<std::mutex> l(mu_);
  return received_;
}

void FirmwareSim::reply(const std::string& text) {
  if (master_ < 0) return;
  const std::string line = text + "\n";
  if (write(master_, line.data(), line.size()) < 0) return;
}

void FirmwareSim::run() {
  while (!stop_ && master_ >= 0) {
    pollfd p{master_, POLLIN, 0};
    if (poll(&p, 1, 5) > 0 && (p.revents & POLLIN)) {
      char buf[256];
      const ssize_t n = read(master_, buf, sizeof buf);
      for (ssize_t i = 0; i < n; ++i) {
        if (grbl_ && buf[i] == '?') {  // realtime status request, outside the line buffer
          if (!silent_)
            reply(grbl_queue_.empty() ? "<Idle|MPos:0.000,0.000,0.000|FS:0,0>"
                                      : "<Run|MPos:0.000,0.000,0.000|FS:0,0>");
        } else if (buf[i] == '\n' || buf[i] == '\r') {  // both end a line, as in Marlin and GRBL
          if (!pending_.empty()) on_line(pending_);
          pending_.clear();
        } else {
          pending_ += buf[i];
        }
      }
    }
    if (grbl_) grbl_execute();
  }
}

void FirmwareSim::on_line(const std::string& line) {
  {
    std::lock_guard<std::mutex> l(mu_);
    received_.push_back(line);
  }
  if (halted_ || silent_) return;
  if (!grbl_) return marlin(line);
  grbl_queue_.push_back(line);
  std::size_t bytes = 0;
  for (const auto& q : grbl_queue_) bytes += q.size() + 1;
  max_buffered_ = std::max(max_buffered_, bytes);
}

// Counts and records a command unless a fault strikes it: the port vanishes, or the
// firmware answers `fatal` and halts. True when the command ran (an "ok" is due).
bool FirmwareSim::run_command(const std::string& command, const std::string& fatal) {
  ++count_;
  if (count_ == f_.silent_at) {
    silent_ = true;
    return false;
  }
  if (count_ == f_.klipper_error_at) {
    reply("!! Move out of range: 300.000 0.000 0.000 [0.000]");
    reply("ok");
    return false;
  }
  if (count_ == f_.disconnect_at) {
    close(master_);
    master_ = -1;
    close(slave_);
    slave_ = -1;
    return false;
  }
  if (count_ == f_.error_at) {
    halted_ = true;
    reply(fatal);
    return false;
  }
  std::lock_guard<std::mutex> l(mu_);
  executed_.push_back(command);
  return true;
}

// GRBL runs one queued line per loop turn (1 ms), so the buffer really fills up.
void FirmwareSim::grbl_execute() {
  if (grbl_queue_.empty() || halted_) return;
  std::this_thread::sleep_for(std::chrono::milliseconds(1));
  const std::string line = grbl_queue_.front();
  grbl_queue_.erase(grbl_queue_.begin());
  if (!run_command(line, "error:22")) return;
  if (count_ != f_.drop_ok_at) reply("ok");
}

void FirmwareSim::marlin(const std::string& line) {
  if (line.rfind("N", 0) != 0) {  // unnumbered: M110 resets the numbering, M105 probes
    if (line.rfind("M110", 0) == 0) {
      last_n_ = 0;
    } else if (line.rfind("M105", 0) != 0) {
      std::lock_guard<std::mutex> l(mu_);
      executed_.push_back(line);  // any other plain line runs, numbering untouched
    }
    return reply(line.rfind("M105", 0) == 0 ? "ok T:20.0 /0.0 B:20.0 /0.0" : "ok");
  }
  const auto star = line.rfind('*');
  const long n = std::strtol(line.c_str() + 1, nullptr, 10);
  const std::string body = line.substr(0, star);
  const std::string command = body.substr(body.find(' ') + 1);
  const bool bad_sum =
      star == std::string::npos || std::atoi(line.c_str() + star + 1) != machines::checksum(body);
  if (n <= highest_n_) {  // seen before: allowed once per resend request that covered it
    if (may_repeat_.erase(n) == 0) ++unrequested_;
  }
  highest_n_ = std::max(highest_n_, n);
  const auto resend = [&](const std::string& why) {
    reply("Error:" + why + ", Last Line: " + std::to_string(last_n_));
    reply("Resend: " + std::to_string(last_n_ + 1));
    reply("ok");
    ++resends_;
    for (long k = last_n_ + 1; k <= highest_n_; ++k) may_repeat_.insert(k);
  };
  if (bad_sum || (n == f_.corrupt_at && !corrupted_)) {
    corrupted_ = corrupted_ || n == f_.corrupt_at;
    return resend("checksum mismatch");
  }
  const bool m110 = command.rfind("M110", 0) == 0;
  if (n != last_n_ + 1 && !m110) return resend("Line Number is not Last Line Number+1");
  last_n_ = n;
  if (m110 && command.find('N') != std::string::npos) {  // Marlin: "N7 M110 N0" -> last line 0
    last_n_ = std::strtol(command.c_str() + command.find('N') + 1, nullptr, 10);
  }
  if (!run_command(command, "Error:Printer halted. kill() called!")) return;
  if (count_ == f_.busy_at) {
    for (int i = 0; i < 4; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(150));
      reply("echo:busy: processing");
    }
  }
  if (count_ != f_.drop_ok_at) reply("ok");
}

}  // namespace strand::testing
