// A sweep file: a base job plus parameters to vary (lists or ranges, product or zip) and
// `where` constraints; expanded into numbered points, each named from its varied values.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "jobs/job_runner.h"
#include "jobs/sweep_constraint.h"

namespace strand::jobs {

enum class SweepMode { Product, Zip };

struct SweepSpec {
  JobSpec job;
  std::vector<std::string> keys;                   // varied parameters, sorted
  std::vector<std::vector<nlohmann::json>> values;  // values[k] for keys[k]
  SweepMode mode = SweepMode::Product;
  std::vector<Constraint> where;
  std::string stem;  // file name prefix: the job's output stem or the generator name
};

struct SweepPoint {
  int index = 0;                 // 0-based position in expansion order
  std::string name;              // "scaffold_gap-0.8_nozzle-0.4"
  nlohmann::json varied;         // {key: value} for the varied keys
  nlohmann::json params;         // base params with the varied values applied
  std::string dropped;           // reason when a `where` constraint drops the point
  std::string error;             // a constraint could not be evaluated (missing value)
};

// {"job": {...}, "vary": {key: [values] | {"from", "to", "step"}}, "mode", "where": [...]}.
// Throws InputError naming the key path (sweep.vary.gap.step, sweep.where[1], ...).
SweepSpec sweep_spec_from_json(const nlohmann::json& j);

// Values of a range, computed as from + i * step (no accumulated error) and rounded to 12
// significant digits; integers when from, to and step are integers.
std::vector<nlohmann::json> range_values(const nlohmann::json& range, const std::string& where);

// Every point in order (product: the last key varies fastest). Throws InputError when
// every point is dropped or two points would share a name.
std::vector<SweepPoint> expand_points(const SweepSpec& spec);

// "I/N" with 1 <= I <= N; throws InputError naming --shard.
struct Shard {
  int index = 1;
  int count = 1;
};
Shard parse_shard(const std::string& text);
// Points are dealt round-robin: point p belongs to shard (p mod N) + 1.
bool in_shard(int point_index, const Shard& shard);

}  // namespace strand::jobs
