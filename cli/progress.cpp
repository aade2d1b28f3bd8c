// Progress bar and plain progress lines.
#include "cli/progress.h"

#include <cmath>
#include <cstdio>

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

}  // namespace strand::cli
