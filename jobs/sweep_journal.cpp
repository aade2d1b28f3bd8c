// Journal lines and the flock(2) that makes a shard run once at a time.
#include "jobs/sweep_journal.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <fstream>
#include <thread>

#include "jobs/sweep_manifest.h"
#include "slicer/input_error.h"

namespace strand::jobs {

namespace {

std::string shard_text(const Shard& s) { return std::to_string(s.index) + "/" + std::to_string(s.count); }

void write_all(int fd, const std::string& text, const std::string& path) {
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw InputError(path + ": cannot append to the sweep journal");
    done += static_cast<std::size_t>(n);
  }
}

}  // namespace

std::string journal_file_name(const Shard& shard) {
  const std::string name = manifest_file_name(shard);
  return name.substr(0, name.size() - 5) + ".journal.jsonl";
}

SweepJournal::SweepJournal(const std::string& path, const Shard& shard, std::size_t sweep_points)
    : path_(path) {
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd_ < 0) throw InputError(path + ": cannot create the sweep journal");
  // A few tries: a status reader holds the lock for microseconds; a running shard for good.
  for (int attempt = 0;; ++attempt) {
    if (::flock(fd_, LOCK_EX | LOCK_NB) == 0) break;
    if (attempt == 10) {
      ::close(fd_);
      fd_ = -1;
      throw InputError("--shard = " + shard_text(shard) + ": another strand sweep is running this shard (" +
                       path + " is locked); wait for it or stop it");
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  const nlohmann::json header = {{"journal", shard_text(shard)}, {"sweep_points", sweep_points}};
  write_all(fd_, header.dump() + "\n", path_);
}

SweepJournal::~SweepJournal() {
  if (fd_ >= 0) ::close(fd_);  // closing releases the lock
}

void SweepJournal::append(const nlohmann::json& row) { write_all(fd_, row.dump() + "\n", path_); }

void SweepJournal::finish() {
  ::unlink(path_.c_str());
  ::close(fd_);
  fd_ = -1;
}

std::map<std::string, nlohmann::json> journal_rows(const std::string& path) {
  std::map<std::string, nlohmann::json> rows;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    const nlohmann::json r = nlohmann::json::parse(line, nullptr, false);
    if (r.is_object() && r.contains("name") && r["name"].is_string()) rows[r["name"].get<std::string>()] = r;
  }
  return rows;
}

std::size_t journal_sweep_points(const std::string& path) {
  std::size_t points = 0;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    const nlohmann::json r = nlohmann::json::parse(line, nullptr, false);
    if (r.is_object() && r.contains("sweep_points") && r["sweep_points"].is_number_unsigned()) {
      points = r["sweep_points"].get<std::size_t>();
    }
  }
  return points;
}

bool journal_in_use(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  const bool busy = ::flock(fd, LOCK_SH | LOCK_NB) != 0 && errno == EWOULDBLOCK;
  ::close(fd);
  return busy;
}

}  // namespace strand::jobs
