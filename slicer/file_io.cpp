// Whole-file reads, output transactions and the temp-file cleanup on signals.
#include "slicer/file_io.h"

#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "slicer/input_error.h"

namespace strand::slicer {

namespace fs = std::filesystem;

namespace {

// Temp files that exist right now, for the signal handler: fixed slots of heap-copied
// paths, claimed and released with atomics (a handler may not lock). A temp that finds no
// free slot is still removed by the normal error paths.
constexpr std::size_t kTempSlots = 256;
std::atomic<char*> g_temps[kTempSlots];

void register_temp(const std::string& path) {
  char* copy = strdup(path.c_str());
  for (auto& slot : g_temps) {
    char* expected = nullptr;
    if (slot.compare_exchange_strong(expected, copy)) return;
  }
  std::free(copy);
}

void forget_temp(const std::string& path) {
  for (auto& slot : g_temps) {
    char* p = slot.load();
    if (p && path == p && slot.compare_exchange_strong(p, nullptr)) {
      std::free(p);
      return;
    }
  }
}

extern "C" void remove_temps_and_die(int sig) {
  for (auto& slot : g_temps) {
    if (char* p = slot.load()) unlink(p);
  }
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

bool same_file(const std::string& a, const std::string& b) {
  std::error_code ec;
  if (fs::equivalent(a, b, ec)) return true;
  const fs::path ca = fs::weakly_canonical(a, ec), cb = fs::weakly_canonical(b, ec);
  return !ec && ca == cb;
}

// Creates the temp file of `target`, registered for the signal cleanup.
std::unique_ptr<std::ofstream> open_temp(const std::string& target, const std::string& temp) {
  std::error_code ec;
  if (fs::is_directory(target, ec)) throw InputError("output = " + target + ": is a directory");
  register_temp(temp);
  auto out = std::make_unique<std::ofstream>(temp, std::ios::binary | std::ios::trunc);
  if (!*out) {
    forget_temp(temp);
    throw InputError("output = " + target + ": cannot write here (check the directory)");
  }
  return out;
}

// Flushes and closes a temp file; on a failed write removes it and throws.
void close_temp(std::ofstream& out, const std::string& target, const std::string& temp) {
  out.flush();
  const bool ok = static_cast<bool>(out);
  out.close();
  if (!ok) {
    std::error_code ec;
    fs::remove(temp, ec);
    forget_temp(temp);
    throw InputError("output = " + target + ": write failed (disk full?)");
  }
}

void write_temp(const std::string& target, const std::string& temp, const std::string& content) {
  auto out = open_temp(target, temp);
  out->write(content.data(), static_cast<std::streamsize>(content.size()));
  close_temp(*out, target, temp);
}

}  // namespace

OutputFiles::~OutputFiles() {
  if (committed_) return;
  for (const Staged& s : staged_) {
    std::error_code ec;
    if (s.stream) s.stream->close();
    fs::remove(s.temp, ec);
    forget_temp(s.temp);
  }
}

void OutputFiles::protect_input(const std::string& path) { protected_.push_back(path); }

void OutputFiles::check_target(const std::string& path) const {
  for (const std::string& input : protected_) {
    if (same_file(path, input)) {
      throw InputError("output = " + path + ": would overwrite the input " + input +
                       " (choose another output name)");
    }
  }
  for (const Staged& s : staged_) {
    if (same_file(path, s.target)) {
      throw InputError("output = " + path + ": named twice among this command's outputs");
    }
  }
}

void OutputFiles::stage(const std::string& path, const std::string& content) {
  check_target(path);
  Staged s{path, path + ".strand-tmp", nullptr};
  write_temp(s.target, s.temp, content);
  staged_.push_back(std::move(s));
}

std::ostream& OutputFiles::stage_stream(const std::string& path) {
  check_target(path);
  Staged s{path, path + ".strand-tmp", nullptr};
  s.stream = open_temp(s.target, s.temp);
  staged_.push_back(std::move(s));
  return *staged_.back().stream;
}

void OutputFiles::commit() {
  for (Staged& s : staged_) {
    if (!s.stream) continue;
    // A failed write removes that temp; the destructor removes the others.
    auto stream = std::move(s.stream);
    try {
      close_temp(*stream, s.target, s.temp);
    } catch (...) {
      s.temp.clear();
      throw;
    }
  }
  for (std::size_t i = 0; i < staged_.size(); ++i) {
    std::error_code ec;
    fs::rename(staged_[i].temp, staged_[i].target, ec);
    if (ec) {
      // Earlier files are already in place; the rest are removed by the destructor.
      staged_.erase(staged_.begin(), staged_.begin() + static_cast<std::ptrdiff_t>(i));
      throw InputError("output = " + staged_.front().target +
                       ": cannot rename the finished file into place");
    }
    forget_temp(staged_[i].temp);
  }
  committed_ = true;
}

void write_file_atomic(const std::string& path, const std::string& content) {
  OutputFiles out;
  out.stage(path, content);
  out.commit();
}

std::string read_file(const std::string& path) {
  std::error_code ec;
  const auto status = fs::status(path, ec);
  if (ec || !fs::exists(status)) throw InputError("input = " + path + ": no such file");
  if (fs::is_directory(status)) throw InputError("input = " + path + ": is a directory, not a file");
  if (fs::is_regular_file(status)) {
    const auto size = fs::file_size(path, ec);
    if (!ec && size > kMaxInputBytes) {
      throw InputError("input = " + path + ": " + std::to_string(size >> 20) +
                       " MiB, larger than the " + std::to_string(kMaxInputBytes >> 20) +
                       " MiB limit");
    }
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("input = " + path + ": cannot read the file");
  std::string text;
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    text.append(buffer, static_cast<std::size_t>(in.gcount()));
    if (text.size() > kMaxInputBytes) {
      throw InputError("input = " + path + ": larger than the " +
                       std::to_string(kMaxInputBytes >> 20) + " MiB limit");
    }
  }
  if (in.bad()) throw InputError("input = " + path + ": cannot read the file");
  return text;
}

void install_signal_cleanup() {
  std::signal(SIGINT, remove_temps_and_die);
  std::signal(SIGTERM, remove_temps_and_die);
}

}  // namespace strand::slicer
