// FNV-1a 64 with the published offset basis and prime.
#include "jobs/content_hash.h"

#include <cstdint>
#include <cstdio>

namespace strand::jobs {

std::string fnv1a_hex(std::string_view bytes) {
  constexpr std::uint64_t kOffsetBasis = 14695981039346656037ULL;
  constexpr std::uint64_t kPrime = 1099511628211ULL;
  std::uint64_t h = kOffsetBasis;
  for (const char c : bytes) {
    h ^= static_cast<unsigned char>(c);
    h *= kPrime;
  }
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
  return text;
}

}  // namespace strand::jobs
