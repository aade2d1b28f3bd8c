// Progress on stderr. Sweeps: a redrawn bar with counts and ETA on a terminal, one plain
// line per finished point otherwise (logs of cluster jobs). Long commands (generators, slice,
// plot, trace, check, preview): a bar with the phase and the time left on a terminal, one
// plain line per phase otherwise; nothing with the global --quiet.
#pragma once

#include <chrono>
#include <cstddef>
#include <functional>
#include <memory>
#include <ostream>
#include <string>

#include "slicer/progress_listener.h"

namespace strand::cli {

class ProgressBar {
 public:
  ProgressBar(std::ostream& out, bool terminal);
  // `name` and `status` describe the point just finished; a status starting with "failed"
  // is also printed on its own line on a terminal.
  void update(std::size_t done, std::size_t total, std::size_t failed, const std::string& name,
              const std::string& status);
  void finish();

 private:
  std::ostream& out_;
  bool terminal_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_;
};

// "1:05", "12:00:03": seconds as a clock for ETAs.
std::string clock_text(double seconds);

// The global flags: --quiet (no progress at all), --progress (plain lines from the first
// phase, even of short runs); Auto otherwise.
enum class ProgressMode { Auto, Quiet, Always };
void set_progress_mode(ProgressMode mode);
ProgressMode progress_mode();
// Where the sweep and send bars go: stderr, or nowhere with --quiet.
std::ostream& progress_stream();

// The phases of one command run (slicer::Progress, passed down into the core). On a
// terminal: one line redrawn in place, "slice [######......] 2/5 slicing layers 12/40  0:03
// elapsed, 0:05 left", erased at the end. Otherwise one line per phase, "slice: 2/5 slicing
// layers (1.3 s)", and "slice: done in 4.2 s" at the end; in mode Auto only once the run has
// lasted `plain_after_s` (short runs print nothing, so their stderr stays empty).
class PhaseProgress : public slicer::Progress {
 public:
  using Clock = std::function<double()>;  // seconds since any fixed point
  // `phases` is how many phases the run expects (each is that share of the bar; more may
  // come); `width` cuts the terminal line (0: never).
  PhaseProgress(std::ostream& out, bool terminal, std::string command, std::size_t phases,
                double plain_after_s = 1.0, Clock clock = {}, std::size_t width = 0);
  // Erases the bar; prints "done" only when the run was not ended by an exception.
  ~PhaseProgress() override;
  PhaseProgress(const PhaseProgress&) = delete;
  PhaseProgress& operator=(const PhaseProgress&) = delete;

  void phase(const std::string& name, std::size_t steps = 0) override;
  void step(std::size_t done) override;
  // Erases the bar before the command prints on stdout; the next event redraws it.
  void clear();
  // Erases the bar; plain lines end with "command: done in X s" if any was printed.
  void finish();

 private:
  double now() const;
  void draw(double now);
  void plain_line(double now);

  std::ostream& out_;
  bool terminal_;
  std::string command_;
  std::size_t phases_;
  double plain_after_s_;
  Clock clock_;
  std::size_t width_;
  double start_ = 0.0, last_draw_ = -1.0;
  std::size_t index_ = 0, steps_ = 0, done_ = 0;
  std::string name_;
  bool drawn_ = false, phase_printed_ = false, any_printed_ = false, finished_ = false;
};

// The progress of a command run on stderr (a bar when it is a terminal), or null with
// --quiet. `command` names it in every line; `phases` as for PhaseProgress.
std::unique_ptr<PhaseProgress> command_progress(const std::string& command, std::size_t phases);

}  // namespace strand::cli
