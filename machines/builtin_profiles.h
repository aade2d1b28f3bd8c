// The shipped profiles (machines/profiles/*.json), embedded at build time.
#pragma once

#include <string>
#include <vector>

namespace strand::machines {

struct BuiltinProfile {
  const char* name;
  const char* json;
};
const std::vector<BuiltinProfile>& builtin_profiles();

}  // namespace strand::machines
