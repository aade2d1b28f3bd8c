// Sweep manifests: manifest.json (every point's parameters, figures, check, file and hash),
// manifest.csv (the same as a flat table), shard manifests and their merge.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "jobs/sweep_spec.h"

namespace strand::jobs {

// "manifest.json" for 1/1, else "manifest-shard-I-of-N.json".
std::string manifest_file_name(const Shard& shard);

// {"sweep": {generator, machine, mode, vary, points, sweep_hash}, "points": rows} plus
// "shard": "I/N" for a shard. `source` is the sweep file's JSON (hashed).
nlohmann::json make_manifest(const SweepSpec& spec, const nlohmann::json& source,
                             const std::vector<nlohmann::json>& rows, const Shard& shard);

// One header line, then one line per point in index order. Columns: index, name, status,
// the varied parameters, figures, derived.* (union over points), check, output, hash, error.
std::string manifest_csv(const nlohmann::json& manifest);

// Writes the shard's manifest JSON, or for 1/1 manifest.json, manifest.csv and index.html;
// each file atomically.
void write_manifest(const nlohmann::json& manifest, const std::string& dir, const Shard& shard);

// Shard manifests of one sweep (same sweep_hash, every shard 1..N exactly once) into the
// manifest the unsharded run writes. Throws InputError naming the offending file.
nlohmann::json merge_manifests(const std::vector<nlohmann::json>& shards,
                               const std::vector<std::string>& paths);

}  // namespace strand::jobs
