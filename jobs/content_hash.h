// Content hashes for sweep manifests: 64-bit FNV-1a (Fowler-Noll-Vo), written as 16 hex
// digits. Not cryptographic; it detects changed or truncated files and changed parameters.
#pragma once

#include <string>
#include <string_view>

namespace strand::jobs {

std::string fnv1a_hex(std::string_view bytes);

}  // namespace strand::jobs
