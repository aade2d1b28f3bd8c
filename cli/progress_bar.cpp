// Progress bar and plain progress lines.
#include "cli/progress_bar.h"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <iostream>
#include <streambuf>
#include <utility>

namespace strand::cli {

ProgressBar::ProgressBar(std::ostream& out, bool terminal)
    : out_(out), terminal_(terminal), start_(std::chrono::steady_clock::now()) {}

std::string clock_text(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  char text[32];
  if (s >= 3600) {
    std::snprintf(text, sizeof text, "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  } else {
    std::snprintf(text, sizeof text, "%ld:%02ld", s / 60, s % 60);
  }
  return text;
}

void ProgressBar::update(std::size_t done, std::size_t total, std::size_t failed,
                         const std::string& name, const std::string& status) {
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double eta = done > 0 ? elapsed / static_cast<double>(done) * static_cast<double>(total - done) : 0.0;
  if (!terminal_) {
    out_ << "sweep: " << done << "/" << total << " " << name << " " << status << "\n";
    return;
  }
  // A failure keeps its own line above the bar so its error stays readable.
  if (status.rfind("failed", 0) == 0) out_ << "\r\033[K" << name << " " << status << "\n";
  constexpr int kBarWidth = 30;
  const int filled = total ? static_cast<int>(kBarWidth * done / total) : kBarWidth;
  out_ << "\r[" << std::string(static_cast<std::size_t>(filled), '#')
       << std::string(static_cast<std::size_t>(kBarWidth - filled), '.') << "] " << done << "/" << total;
  if (failed) out_ << ", " << failed << " failed";
  out_ << "  elapsed " << clock_text(elapsed) << "  ETA " << clock_text(eta) << "   " << std::flush;
  drawn_ = true;
}

void ProgressBar::finish() {
  if (drawn_) out_ << "\n";
  drawn_ = false;
}

namespace {

ProgressMode g_mode = ProgressMode::Auto;

// An output stream that drops everything (progress with --quiet).
class NullBuffer : public std::streambuf {
 protected:
  int overflow(int c) override { return traits_type::not_eof(c); }
  std::streamsize xsputn(const char*, std::streamsize n) override { return n; }
};

std::string seconds_text(double s) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f s", std::max(0.0, s));
  return text;
}

double steady_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

void set_progress_mode(ProgressMode mode) { g_mode = mode; }
ProgressMode progress_mode() { return g_mode; }

std::ostream& progress_stream() {
  static NullBuffer buffer;
  static std::ostream null(&buffer);
  return g_mode == ProgressMode::Quiet ? null : std::cerr;
}

PhaseProgress::PhaseProgress(std::ostream& out, bool terminal, std::string command,
                             std::size_t phases, double plain_after_s, Clock clock,
                             std::size_t width)
    : out_(out),
      terminal_(terminal),
      command_(std::move(command)),
      phases_(std::max<std::size_t>(phases, 1)),
      plain_after_s_(plain_after_s),
      clock_(clock ? std::move(clock) : Clock(steady_seconds)),
      width_(width) {
  start_ = now();
}

PhaseProgress::~PhaseProgress() {
  if (std::uncaught_exceptions() > 0) {
    clear();  // the error line follows on a clean line; no "done"
    finished_ = true;
    return;
  }
  finish();
}

double PhaseProgress::now() const { return clock_(); }

void PhaseProgress::phase(const std::string& name, std::size_t steps) {
  if (finished_) return;
  ++index_;
  name_ = name;
  steps_ = steps;
  done_ = 0;
  phase_printed_ = false;
  const double t = now();
  if (terminal_) {
    draw(t);
  } else {
    plain_line(t);
  }
}

void PhaseProgress::step(std::size_t done) {
  if (finished_) return;
  done_ = std::min(done, steps_);
  const double t = now();
  if (terminal_) {
    if (t - last_draw_ >= 0.1) draw(t);  // at most ten redraws a second
  } else if (!phase_printed_) {
    plain_line(t);  // a long phase is named once the run passes the threshold
  }
}

void PhaseProgress::plain_line(double t) {
  if (index_ == 0) return;
  if (g_mode != ProgressMode::Always && t - start_ < plain_after_s_) return;
  out_ << command_ << ": " << index_ << "/" << std::max(phases_, index_) << " " << name_ << " ("
       << seconds_text(t - start_) << ")\n"
       << std::flush;
  phase_printed_ = any_printed_ = true;
}

void PhaseProgress::draw(double t) {
  if (index_ == 0) return;
  last_draw_ = t;
  const double total = static_cast<double>(std::max(phases_, index_));
  const double within = steps_ ? static_cast<double>(done_) / static_cast<double>(steps_) : 0.0;
  const double f = std::clamp((static_cast<double>(index_ - 1) + within) / total, 0.0, 1.0);
  const double elapsed = t - start_;
  constexpr int kBarWidth = 20;
  const int filled = static_cast<int>(kBarWidth * f);
  std::string line = command_ + " [" + std::string(static_cast<std::size_t>(filled), '#') +
                     std::string(static_cast<std::size_t>(kBarWidth - filled), '.') + "] " +
                     std::to_string(index_) + "/" + std::to_string(std::max(phases_, index_)) +
                     " " + name_;
  if (steps_) line += " " + std::to_string(done_) + "/" + std::to_string(steps_);
  line += "  " + clock_text(elapsed) + " elapsed";
  if (f > 0.0) line += ", " + clock_text(elapsed * (1.0 - f) / f) + " left";
  if (width_ > 1 && line.size() > width_ - 1) line.resize(width_ - 1);
  out_ << "\r\033[K" << line << std::flush;
  drawn_ = true;
}

void PhaseProgress::clear() {
  if (!drawn_) return;
  out_ << "\r\033[K" << std::flush;
  drawn_ = false;
}

void PhaseProgress::finish() {
  if (finished_) return;
  finished_ = true;
  clear();
  if (any_printed_) out_ << command_ << ": done in " << seconds_text(now() - start_) << "\n" << std::flush;
}

std::unique_ptr<PhaseProgress> command_progress(const std::string& command, std::size_t phases) {
  if (g_mode == ProgressMode::Quiet) return nullptr;
  const bool terminal = ::isatty(STDERR_FILENO) != 0;
  std::size_t width = 0;
  winsize ws{};
  if (terminal && ::ioctl(STDERR_FILENO, TIOCGWINSZ, &ws) == 0) width = ws.ws_col;
  return std::make_unique<PhaseProgress>(std::cerr, terminal, command, phases, 1.0,
                                         PhaseProgress::Clock{}, width);
}

}  // namespace strand::cli
