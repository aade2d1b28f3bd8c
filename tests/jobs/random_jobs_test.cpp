// Every file a generator writes passes `strand check` against its machine: 500 seeded random
// valid jobs per generator, each planned and emitted for every printer profile, parsed back
// and checked (crossings, bounds, arcs, numbers); every fifth is also planned whole and must
// give the same bytes as the layer-by-layer pipeline. Random sets start from the sample job and
// scale its numbers; sets the generator refuses (InputError) are drawn again.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <sstream>

#include "jobs/job_runner.h"
#include "machines/profile.h"
#include "postprocess/inspect/check.h"
#include "slicer/input_error.h"
#include "tests/support/sample_jobs.h"

namespace strand::jobs {
namespace {

constexpr int kJobsPerGenerator = 500;
constexpr int kMaxDraws = 20 * kJobsPerGenerator;

// The sample's parameters with numbers scaled by 0.6-1.6, small counts, two layers.
nlohmann::json random_params(const nlohmann::json& sample, std::mt19937& rng) {
  std::uniform_real_distribution<double> scale(0.6, 1.6);
  std::uniform_int_distribution<int> count(1, 4);
  nlohmann::json p = sample;
  p.erase("height");
  p["layers"] = 2;
  for (auto& [key, value] : p.items()) {
    if (key == "layers" || key == "speed") continue;
    if (key == "rows" || key == "cols") {
      value = count(rng);
    } else if (value.is_number()) {
      value = std::round(value.get<double>() * scale(rng) * 1000.0) / 1000.0;
    }
  }
  if (p.contains("size")) p["size"] = std::to_string(10 + count(rng) * 5) + "x" + std::to_string(10 + count(rng) * 4);
  return p;
}

std::vector<machines::MachineProfile> printers() {
  std::vector<machines::MachineProfile> out;
  for (const auto& [name, description] : machines::list_profiles()) {
    machines::MachineProfile m = machines::load_profile(name);
    const bool planar = m.volume.kind == machines::KinematicsKind::Delta ||
                        m.volume.kind == machines::KinematicsKind::Cartesian;
    if (!m.plotter.enabled && planar) out.push_back(std::move(m));
  }
  return out;
}

class RandomJobs : public ::testing::TestWithParam<std::string> {};

TEST_P(RandomJobs, EveryWrittenFilePassesCheckOnEveryPrinter) {
  const auto& spec = *patterns::find_generator(GetParam());
  const auto machines = printers();
  ASSERT_GE(machines.size(), 5u);
  std::mt19937 rng(20261122);
  int valid = 0, draws = 0;
  while (valid < kJobsPerGenerator && draws++ < kMaxDraws) {
    const nlohmann::json params = random_params(testing::sample_params().at(spec.name), rng);
    slicer::Toolpath t;
    try {
      t = spec.generate(slicer::resolve_params(spec.table(), params));
    } catch (const InputError&) {
      continue;
    }
    ++valid;
    for (const auto& m : machines) {
      post::Produced out;
      const post::PlanOptions options = post::plan_options_from(t, slicer::kDefaultArcToleranceMm);
      try {
        out = post::produce(t, m, options, "x.gcode");
      } catch (const InputError&) {
        continue;  // does not fit this machine: refused, nothing written
      }
      if (valid % 5 == 0) {
        const post::Produced whole = post::produce_program(t, post::plan(t, m, options), m, options, "x.gcode");
        ASSERT_EQ(out.gcode, whole.gcode) << spec.name << " on " << m.name << " with " << params.dump()
                                          << ": layer by layer differs from the whole program";
      }
      post::CheckOptions o;
      o.machine = &m;
      o.touch_mm = slicer::kGcodeResolutionMm;
      const post::CheckReport report = post::check_gcode(out.gcode, o);
      ASSERT_TRUE(report.ok()) << spec.name << " on " << m.name << " with " << params.dump()
                               << ":\n" << post::to_text(report);
      // No move without an axis word but the named E-only ones (prime, suck-back).
      std::istringstream lines(out.gcode);
      for (std::string line; std::getline(lines, line);) {
        if (line.rfind("G1 ", 0) != 0 || line.find(';') != std::string::npos) continue;
        ASSERT_TRUE(line.find(" X") != std::string::npos || line.find(" Y") != std::string::npos ||
                    line.find(" Z") != std::string::npos)
            << spec.name << " on " << m.name << " with " << params.dump() << ": " << line;
      }
    }
  }
  EXPECT_EQ(valid, kJobsPerGenerator) << "only " << valid << " valid sets in " << kMaxDraws << " draws";
}

INSTANTIATE_TEST_SUITE_P(Generators, RandomJobs,
                         ::testing::Values("scaffold", "tetrachiral", "hexachiral", "missing-rib",
                                           "reentrant"),
                         [](const auto& info) {
                           std::string n = info.param;
                           std::replace(n.begin(), n.end(), '-', '_');
                           return n;
                         });

}  // namespace
}  // namespace strand::jobs
