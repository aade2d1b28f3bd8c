// Fuzz target: any bytes as a job file, a sweep file and a machine profile, each through the
// same bounded parser and checks as the CLI; and as the --tools text.
#include <cstddef>
#include <cstdint>
#include <string>

#include "jobs/job_runner.h"
#include "jobs/sweep_spec.h"
#include "machines/profile.h"
#include "postprocess/plan/tool_assignment.h"
#include "slicer/input_error.h"
#include "slicer/json_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace strand;
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    post::tool_assignment_from_text(text, "tools");
  } catch (const InputError&) {
  }
  nlohmann::json j;
  try {
    j = slicer::parse_json(text, "fuzz");
  } catch (const InputError&) {
    return 0;
  }
  try {
    jobs::job_spec_from_json(j, "job");
  } catch (const InputError&) {
  }
  try {
    jobs::expand_points(jobs::sweep_spec_from_json(j));
  } catch (const InputError&) {
  }
  try {
    machines::profile_from_json(j, "machine fuzz");
  } catch (const InputError&) {
  }
  return 0;
}
