// Job running without printing: job files checked by key path, produce_job is what
// run_job writes.
#include "jobs/job_runner.h"

#include <gtest/gtest.h>

#include "machines/profile.h"
#include "slicer/input_error.h"
#include "slicer/tolerances.h"
#include "tests/support/cli_runner.h"

namespace strand::jobs {
namespace {

const nlohmann::json kJob = {{"generator", "scaffold"},
                             {"params", {{"nozzle", 0.84}, {"gap", 1.6}, {"size", "20x20"}, {"height", 3}}}};

TEST(JobRunner, ProduceJobIsWhatRunJobWrites) {
  const auto dir = strand::testing::fresh_dir("job-runner");
  JobSpec spec = job_spec_from_json(kJob, "job");
  spec.settings.output = dir + "/a.gcode";
  spec.settings.report = dir + "/a.json";
  const auto produced = produce_job(*spec.generator, spec.params, spec.settings);
  EXPECT_FALSE(strand::testing::exists(dir + "/a.gcode"));
  run_job(*spec.generator, spec.params, spec.settings);
  EXPECT_EQ(strand::testing::slurp(dir + "/a.gcode"), produced.gcode);
  EXPECT_EQ(nlohmann::json::parse(strand::testing::slurp(dir + "/a.json")), produced.report);
}

// Issue 29: nothing deposited is never a file (the slice's own message is more specific;
// this guards every job, the slice's and the generators').
TEST(JobRunner, AProducedFileWithoutDepositIsRefused) {
  const auto machine = machines::load_profile("deltawasp-2040-clay");
  post::Produced empty;
  empty.report = {{"generator", "slice"},
                  {"totals", {{"deposit_length_mm", 0.0}, {"layers", 7}}}};
  try {
    vet_produced(empty, machine, slicer::kDefaultArcToleranceMm);
    ADD_FAILURE() << "an empty file passed";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "slice: every layer is empty (7 layers, nothing deposited)");
  }
  JobSpec spec = job_spec_from_json(kJob, "job");
  const auto produced = produce_job(*spec.generator, spec.params, spec.settings);
  EXPECT_NO_THROW(vet_produced(produced, machine, slicer::kDefaultArcToleranceMm));
}

TEST(JobRunner, DefaultOutputIsNamedAfterTheGenerator) {
  const JobSpec spec = job_spec_from_json(kJob, "job");
  EXPECT_EQ(job_output_path(*spec.generator, spec.settings), "scaffold.gcode");
  EXPECT_EQ(spec.settings.machine, "deltawasp-2040-clay");
}

TEST(JobRunner, ProblemsNameTheKeyPath) {
  nlohmann::json unknown = kJob;
  unknown["nozzle"] = 1;
  EXPECT_THROW(
      try { job_spec_from_json(unknown, "sweep.job"); } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("sweep.job.nozzle: unknown key"), std::string::npos) << e.what();
        throw;
      },
      InputError);
  nlohmann::json bad_value = kJob;
  bad_value["params"]["nozzle"] = 0;
  const JobSpec spec = job_spec_from_json(bad_value, "job");
  EXPECT_THROW(produce_job(*spec.generator, spec.params, spec.settings), InputError);
}

}  // namespace
}  // namespace strand::jobs
