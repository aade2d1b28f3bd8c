// mmap + madvise(MADV_HUGEPAGE) for large pieces (see large_allocator.h).
#include "slicer/large_allocator.h"

#include <sys/mman.h>

#include <cstdint>
#include <new>

namespace strand::slicer {

namespace {

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kMapLargePieces = false;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(memory_sanitizer)
constexpr bool kMapLargePieces = false;
#else
constexpr bool kMapLargePieces = true;
#endif
#else
constexpr bool kMapLargePieces = true;
#endif

std::size_t rounded(std::size_t bytes) { return (bytes + kLargePieceBytes - 1) / kLargePieceBytes * kLargePieceBytes; }

}  // namespace

void* large_allocate(std::size_t bytes) {
  if (!kMapLargePieces || bytes < kLargePieceBytes) return ::operator new(bytes);
  if (bytes > (std::size_t{1} << 46)) throw std::bad_alloc();
  const std::size_t size = rounded(bytes);
  // Map one huge page more than needed and unmap the unaligned head and tail.
  void* raw = ::mmap(nullptr, size + kLargePieceBytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (raw == MAP_FAILED) throw std::bad_alloc();
  const auto start = reinterpret_cast<std::uintptr_t>(raw);
  const std::uintptr_t aligned = (start + kLargePieceBytes - 1) / kLargePieceBytes * kLargePieceBytes;
  if (aligned > start) ::munmap(raw, aligned - start);
  const std::size_t tail = start + size + kLargePieceBytes - (aligned + size);
  if (tail > 0) ::munmap(reinterpret_cast<void*>(aligned + size), tail);
  ::madvise(reinterpret_cast<void*>(aligned), size, MADV_HUGEPAGE);  // advice only: fine if refused
  return reinterpret_cast<void*>(aligned);
}

bool large_pieces_mapped() { return kMapLargePieces; }

void large_deallocate(void* p, std::size_t bytes) noexcept {
  if (!p) return;
  if (!kMapLargePieces || bytes < kLargePieceBytes) {
    ::operator delete(p);
    return;
  }
  ::munmap(p, rounded(bytes));
}

}  // namespace strand::slicer
