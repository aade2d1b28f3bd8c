// Whole-file reads, output transactions and the temp-file cleanup on signals.
#include "slicer/file_io.h"

#include <fcntl.h>
#include <pthread.h>
#include <sys/file.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string_view>
#include <stdexcept>
#include <system_error>
#include <vector>

#include "slicer/input_error.h"

namespace strand::slicer {

namespace fs = std::filesystem;

namespace {

constexpr std::string_view kJournalHeader = "strand output set v1";
constexpr std::size_t kMaxJournalBytes = std::size_t{1} << 20;

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

// Writes `head` into `joined`, then the whole of `body`, copied by the kernel (a plain
// read/write loop where copy_file_range cannot copy between these files), and renames the
// result to `body`'s name (the name a journal recognises as this target's temp). On failure
// both are removed and InputError names `target`.
void join_head(const std::string& target, const std::string& head, const std::string& body,
               const std::string& joined) {
  register_temp(joined);
  const int in = ::open(body.c_str(), O_RDONLY | O_CLOEXEC);
  const int out = ::open(joined.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  bool ok = in >= 0 && out >= 0;
  for (std::size_t done = 0; ok && done < head.size();) {
    const ssize_t n = ::write(out, head.data() + done, head.size() - done);
    ok = n > 0;
    if (ok) done += static_cast<std::size_t>(n);
  }
  bool kernel_copy = true;
  std::vector<char> buffer;
  while (ok) {
    ssize_t n = -1;
    if (kernel_copy) {
      n = ::copy_file_range(in, nullptr, out, nullptr, std::size_t{1} << 30, 0);
      if (n < 0 && (errno == EXDEV || errno == ENOSYS || errno == EINVAL || errno == EOPNOTSUPP)) {
        kernel_copy = false;
        buffer.resize(std::size_t{1} << 16);
        continue;
      }
    } else {
      n = ::read(in, buffer.data(), buffer.size());
      for (ssize_t w = 0; n > 0 && w < n;) {
        const ssize_t m = ::write(out, buffer.data() + w, static_cast<std::size_t>(n - w));
        if (m <= 0) n = -1;
        else w += m;
      }
    }
    if (n == 0) break;
    ok = n > 0;
  }
  if (in >= 0) ::close(in);
  if (out >= 0 && ::close(out) != 0) ok = false;
  std::error_code ec;
  if (ok) {
    fs::rename(joined, body, ec);
    ok = !ec;
  }
  if (!ok) {
    fs::remove(body, ec);
    forget_temp(body);
    fs::remove(joined, ec);
    forget_temp(joined);
    throw InputError("output = " + target + ": write failed (disk full?)");
  }
  forget_temp(joined);
}

void write_temp(const std::string& target, const std::string& temp, const std::string& content) {
  auto out = open_temp(target, temp);
  out->write(content.data(), static_cast<std::streamsize>(content.size()));
  close_temp(*out, target, temp);
}

// Blocks SIGINT, SIGTERM and SIGHUP in this thread for its lifetime (a pending one is
// delivered when it ends).
class SignalsHeld {
 public:
  SignalsHeld() {
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    sigaddset(&set, SIGTERM);
    sigaddset(&set, SIGHUP);
    pthread_sigmask(SIG_BLOCK, &set, &old_);
  }
  ~SignalsHeld() { pthread_sigmask(SIG_SETMASK, &old_, nullptr); }
  SignalsHeld(const SignalsHeld&) = delete;
  SignalsHeld& operator=(const SignalsHeld&) = delete;

 private:
  sigset_t old_;
};

std::string journal_path(const std::string& first_target) {
  return first_target + ".strand-commit";
}

// The journal of one set's renames: "<temp>\t<target>" per line, absolute paths, written
// whole under a temp name and renamed into place, locked (flock) while this process renames
// so that another strand process never completes a set that is still being committed.
class Journal {
 public:
  Journal(const std::string& first_target,
          const std::vector<std::pair<std::string, std::string>>& renames)
      : path_(journal_path(first_target)) {
    std::string text = std::string(kJournalHeader) + "\n";
    for (const auto& [temp, target] : renames)
      text += fs::absolute(temp).string() + "\t" + fs::absolute(target).string() + "\n";
    const std::string temp = path_ + ".strand-tmp";
    fd_ = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd_ < 0) throw InputError("output = " + first_target + ": cannot write here");
    ::flock(fd_, LOCK_EX);
    bool ok = ::write(fd_, text.data(), text.size()) == static_cast<ssize_t>(text.size());
    ok = ok && ::fsync(fd_) == 0 && std::rename(temp.c_str(), path_.c_str()) == 0;
    if (!ok) {
      ::unlink(temp.c_str());
      ::close(fd_);
      throw InputError("output = " + first_target + ": cannot write here (disk full?)");
    }
  }
  ~Journal() { abandon(); }
  Journal(const Journal&) = delete;
  Journal& operator=(const Journal&) = delete;

  // Every rename done: the journal goes.
  void finish() {
    if (fd_ < 0) return;
    ::unlink(path_.c_str());
    ::close(fd_);
    fd_ = -1;
  }
  // A rename failed: the set cannot be completed, the journal goes with its temps.
  void abandon() { finish(); }

 private:
  std::string path_;
  int fd_ = -1;
};

}  // namespace

bool recover_output_set(const std::string& first_target) {
  const std::string path = journal_path(first_target);
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {  // being committed by another process
    ::close(fd);
    return false;
  }
  std::string text;
  char buffer[4096];
  for (ssize_t n; (n = ::read(fd, buffer, sizeof buffer)) > 0;) {
    text.append(buffer, static_cast<std::size_t>(n));
    if (text.size() > kMaxJournalBytes) break;
  }
  bool completed = false;
  if (text.rfind(std::string(kJournalHeader) + "\n", 0) == 0 && text.size() <= kMaxJournalBytes) {
    std::size_t at = text.find('\n') + 1;
    while (at < text.size()) {
      const std::size_t end = text.find('\n', at);
      if (end == std::string::npos) break;
      const std::string line = text.substr(at, end - at);
      at = end + 1;
      const std::size_t tab = line.find('\t');
      if (tab == std::string::npos) continue;
      const std::string temp = line.substr(0, tab), target = line.substr(tab + 1);
      // Only Strand's own temps are moved: the name of each says what it becomes.
      if (temp != target + ".strand-tmp") continue;
      std::error_code ec;
      if (fs::is_regular_file(fs::symlink_status(temp, ec))) {
        fs::rename(temp, target, ec);
        completed = completed || !ec;
      }
    }
  }
  ::unlink(path.c_str());
  ::close(fd);
  return completed;
}

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
  recover_output_set(path);
  Staged s{path, path + ".strand-tmp", nullptr};
  write_temp(s.target, s.temp, content);
  staged_.push_back(std::move(s));
}

std::ostream& OutputFiles::stage_stream(const std::string& path) {
  check_target(path);
  recover_output_set(path);
  Staged s{path, path + ".strand-tmp", nullptr};
  s.stream = open_temp(s.target, s.temp);
  staged_.push_back(std::move(s));
  return *staged_.back().stream;
}

void OutputFiles::prepend(const std::string& path, std::string head) {
  for (Staged& s : staged_) {
    if (s.target == path && s.stream) {
      s.head = std::move(head);
      return;
    }
  }
  throw std::logic_error("OutputFiles::prepend: " + path + " is not a staged stream");
}

void OutputFiles::commit() {
  for (Staged& s : staged_) {
    if (!s.stream) continue;
    // A failed write removes that temp; the destructor removes the others.
    auto stream = std::move(s.stream);
    try {
      close_temp(*stream, s.target, s.temp);
      if (!s.head.empty()) {
        join_head(s.target, s.head, s.temp, s.target + ".strand-tmp-joined");
        s.head.clear();
      }
    } catch (...) {
      s.temp.clear();
      throw;
    }
  }
  // Several files: a journal naming every rename goes first, so a set interrupted by a kill
  // is completed by the next run (recover_output_set); catchable signals wait until the
  // renames are done, and the temps now belong to the journal, not to the signal cleanup.
  SignalsHeld held;
  std::unique_ptr<Journal> journal;
  if (staged_.size() > 1) {
    std::vector<std::pair<std::string, std::string>> renames;
    for (const Staged& s : staged_) renames.emplace_back(s.temp, s.target);
    journal = std::make_unique<Journal>(staged_.front().target, renames);
    for (const Staged& s : staged_) forget_temp(s.temp);
  }
  for (std::size_t i = 0; i < staged_.size(); ++i) {
    if (rename_hook_) rename_hook_(i);
    std::error_code ec;
    fs::rename(staged_[i].temp, staged_[i].target, ec);
    if (ec) {
      // Earlier files are already in place; the rest are removed by the destructor.
      if (journal) journal->abandon();
      staged_.erase(staged_.begin(), staged_.begin() + static_cast<std::ptrdiff_t>(i));
      throw InputError("output = " + staged_.front().target +
                       ": cannot rename the finished file into place");
    }
    forget_temp(staged_[i].temp);
  }
  if (journal) journal->finish();
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
  if (fs::is_directory(status))
    throw InputError("input = " + path + ": is a directory, not a file");
  // A FIFO would block and a device (/dev/zero) never end: only regular files are read.
  if (fs::is_fifo(status))
    throw InputError("input = " + path + ": is a FIFO (named pipe), not a regular file");
  if (fs::is_character_file(status) || fs::is_block_file(status))
    throw InputError("input = " + path + ": is a device, not a regular file");
  if (fs::is_socket(status))
    throw InputError("input = " + path + ": is a socket, not a regular file");
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
  std::signal(SIGHUP, remove_temps_and_die);
}

}  // namespace strand::slicer
