// Large pieces come mapped on huge-page boundaries and behave as any vector storage; small ones
// come from operator new.
#include "slicer/large_allocator.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <numeric>
#include <vector>

namespace strand::slicer {
namespace {

TEST(LargeAllocator, LargePiecesAreAlignedToHugePagesAndWritable) {
  const std::size_t bytes = 3 * kLargePieceBytes + 123;
  auto* p = static_cast<unsigned char*>(large_allocate(bytes));
  ASSERT_NE(p, nullptr);
  if (large_pieces_mapped()) {
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(p) % kLargePieceBytes, 0u);
  }
  for (std::size_t i = 0; i < bytes; i += 4096) p[i] = static_cast<unsigned char>(i / 4096);
  p[bytes - 1] = 0xab;
  for (std::size_t i = 0; i < bytes; i += 4096) ASSERT_EQ(p[i], static_cast<unsigned char>(i / 4096));
  EXPECT_EQ(p[bytes - 1], 0xab);
  large_deallocate(p, bytes);
}

TEST(LargeAllocator, SmallPiecesComeFromOperatorNew) {
  auto* p = static_cast<int*>(large_allocate(64 * sizeof(int)));
  for (int i = 0; i < 64; ++i) p[i] = i;
  EXPECT_EQ(std::accumulate(p, p + 64, 0), 64 * 63 / 2);
  large_deallocate(p, 64 * sizeof(int));
}

TEST(LargeAllocator, VectorGrowingPastManyHugePagesKeepsItsContents) {
  LargeVector<std::uint64_t> v;
  std::vector<std::uint64_t> reference;
  for (std::uint64_t i = 0; i < 3'000'000; ++i) {  // 24 MB: a dozen reallocations, most mapped
    v.push_back(i * 2654435761u);
    reference.push_back(i * 2654435761u);
  }
  ASSERT_EQ(v.size(), reference.size());
  EXPECT_TRUE(std::equal(v.begin(), v.end(), reference.begin()));
  LargeVector<std::uint64_t> copy = v;
  EXPECT_EQ(copy, v);
  v.clear();
  v.shrink_to_fit();
  EXPECT_EQ(copy.back(), reference.back());
}

}  // namespace
}  // namespace strand::slicer
