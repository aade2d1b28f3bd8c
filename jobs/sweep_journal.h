// A shard's journal, DIR/manifest[-shard-I-of-N].journal.jsonl: one JSON line per finished
// point, appended as points finish, so a run that is killed (Ctrl-C, a Slurm time limit, a
// pre-empted or cancelled array task) keeps its finished points for the next run. The file
// is also the shard's lock: the run holds an exclusive flock(2) on it, so a second run of
// the same shard in the same directory (a resubmitted task while the first still runs) is
// refused instead of running the same points twice at once.
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "jobs/sweep_spec.h"

namespace strand::jobs {

// "manifest.journal.jsonl" for 1/1, else "manifest-shard-I-of-N.journal.jsonl".
std::string journal_file_name(const Shard& shard);

// Open for appending, locked. The first line each run appends is a header,
// {"journal": "I/N", "sweep_points": total}, so `strand sweep --status` knows the size of a
// sweep whose manifest is not written yet; readers skip lines without a "name".
class SweepJournal {
 public:
  // Throws InputError naming --shard when another process holds the lock (after retrying
  // for about a second: `strand sweep --status` takes it for an instant to test it).
  SweepJournal(const std::string& path, const Shard& shard, std::size_t sweep_points);
  ~SweepJournal();
  SweepJournal(const SweepJournal&) = delete;
  SweepJournal& operator=(const SweepJournal&) = delete;
  // One line, flushed to the kernel before returning (a killed process loses nothing).
  void append(const nlohmann::json& row);
  // The manifest is written: the journal is removed while still locked.
  void finish();

 private:
  std::string path_;
  int fd_ = -1;
};

// Point rows by name, later lines winning; a torn last line is skipped.
std::map<std::string, nlohmann::json> journal_rows(const std::string& path);
// The last header's sweep_points, or 0.
std::size_t journal_sweep_points(const std::string& path);
// Whether a run holds the journal's lock now (false when there is no journal).
bool journal_in_use(const std::string& path);

}  // namespace strand::jobs
