// Fuzz target: any bytes as a sweep `where` constraint, parsed and evaluated.
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>

#include "jobs/sweep_constraint.h"
#include "slicer/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace strand;
  try {
    const jobs::Constraint c =
        jobs::parse_constraint(std::string(reinterpret_cast<const char*>(data), size), "where");
    std::map<std::string, double> values;
    for (const auto& name : c.names) values[name] = 1.5;
    jobs::holds(c, values);
  } catch (const InputError&) {
  }
  return 0;
}
