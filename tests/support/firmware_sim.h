// A simulated controller on a pseudo-terminal (openpty) for testing `strand send`: Marlin
// (line numbers, checksums, "Resend:", duplicates refused by line number) or GRBL (a
// 127-byte receive buffer, "ok" per line, '?' status), with faults injected on request.
// Like the real firmware it ends a line at LF or CR, runs unnumbered lines as they come and
// takes a numbered "M110 N<k>" as "the last line was k". It records exactly which commands
// it executed, in order.
#pragma once

#include <atomic>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <vector>

namespace strand::testing {

struct SimFaults {
  int drop_ok_at = 0;        // the ok of the k-th executed command is never sent
  int corrupt_at = 0;        // the first arrival of line k (Marlin) has a "bad checksum"
  int error_at = 0;          // command k answers a fatal error and the firmware halts
  int disconnect_at = 0;     // the port vanishes when command k arrives
  int busy_at = 0;           // command k takes long, with "busy: processing" keep-alives
  int silent_at = 0;         // from command k on the firmware neither runs nor answers anything
  int klipper_error_at = 0;  // command k answers "!! Move out of range" and "ok" (not run)
};

class FirmwareSim {
 public:
  FirmwareSim(bool grbl, SimFaults faults);
  ~FirmwareSim();
  const std::string& port() const { return port_; }
  std::vector<std::string> executed() const;  // command texts, without N and checksum
  std::vector<std::string> received() const;  // every line as it arrived
  int resend_requests() const { return resends_; }
  // Numbered lines that arrived twice without a resend request in between (must be 0).
  int unrequested_duplicates() const { return unrequested_; }
  std::size_t max_buffered() const { return max_buffered_; }  // GRBL: bytes waiting

 private:
  void run();
  void on_line(const std::string& line);
  void marlin(const std::string& line);
  void grbl_execute();
  bool run_command(const std::string& command, const std::string& fatal);
  void reply(const std::string& text);

  bool grbl_;
  SimFaults f_;
  int master_ = -1, slave_ = -1;
  std::string port_;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  mutable std::mutex mu_;
  std::vector<std::string> executed_, received_;
  std::vector<std::string> grbl_queue_;
  std::string pending_;
  long last_n_ = 0;
  int count_ = 0;
  bool halted_ = false, corrupted_ = false, silent_ = false;
  std::atomic<int> resends_{0};
  int unrequested_ = 0;
  std::set<long> may_repeat_;  // numbered lines a resend request asked for again
  long highest_n_ = 0;
  std::size_t max_buffered_ = 0;
};

}  // namespace strand::testing
