// `strand sweep --status -o DIR`: how far a sweep is, shard by shard, read from what the runs
// leave in DIR (shard manifests, journals and their locks, the Slurm submission record), so
// it works the same for a local run, shards run by hand and a Slurm array.
#pragma once

#include <string>
#include <vector>

#include "jobs/sweep_spec.h"

namespace strand::jobs {

enum class ShardState { NotStarted, Running, Stopped, Finished };

struct ShardStatus {
  Shard shard;
  std::size_t points = 0;   // the shard's points (round-robin share of the sweep)
  std::size_t done = 0;     // ok (manifest or journal) or dropped by a `where`
  std::size_t failed = 0;   // listed as failed in the shard's manifest
  ShardState state = ShardState::NotStarted;
  // Not done and not failed: being run now (Running) or waiting for a run.
  std::size_t remaining() const { return points - done - failed; }
};

struct SweepStatus {
  std::size_t points = 0;   // every point of the sweep; 0 when nothing says how many
  std::vector<ShardStatus> shards;
  bool merged = false;      // a sharded sweep's manifest.json is written
};

// Throws InputError when DIR holds nothing of a sweep.
SweepStatus sweep_status(const std::string& dir);

const char* state_name(ShardState s);  // "not started", "running", "stopped", "finished"

}  // namespace strand::jobs
