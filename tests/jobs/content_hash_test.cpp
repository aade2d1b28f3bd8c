// FNV-1a 64 against the published test vectors.
#include "jobs/content_hash.h"

#include <gtest/gtest.h>

namespace strand::jobs {
namespace {

TEST(ContentHash, MatchesPublishedFnv1a64Vectors) {
  EXPECT_EQ(fnv1a_hex(""), "cbf29ce484222325");
  EXPECT_EQ(fnv1a_hex("a"), "af63dc4c8601ec8c");
  EXPECT_EQ(fnv1a_hex("foobar"), "85944171f73967e8");
}

TEST(ContentHash, OneChangedByteChangesTheHash) {
  EXPECT_NE(fnv1a_hex("G1 X1.000"), fnv1a_hex("G1 X1.001"));
}

}  // namespace
}  // namespace strand::jobs
