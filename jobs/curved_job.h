// Jobs on a curved substrate: the substrate parameters checked, the pattern generated flat
// (--wrap patch) or periodic around the cylinder (--wrap full, through the registry's
// generate_wrapped), then produce_curved renders every output of the machine, written as one
// transaction.
#pragma once

#include <nlohmann/json.hpp>

#include "jobs/job_runner.h"
#include "postprocess/plan/produce_curved.h"

namespace strand::jobs {

// In memory; nothing is written. Throws InputError for every bad input (see produce_curved).
post::CurvedProduced produce_curved_job(const patterns::GeneratorSpec& generator,
                                        const nlohmann::json& params, const JobSettings& settings);

// produce_curved_job, then writes all outputs (and the report) together; the summary and
// report come back in a Produced (no G-code in memory).
post::Produced run_curved_job(const patterns::GeneratorSpec& generator,
                              const nlohmann::json& params, const JobSettings& settings);

}  // namespace strand::jobs
