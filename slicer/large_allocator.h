// Memory for the few arrays that grow to tens of megabytes (a large job's moves). Pieces of
// 2 MiB and more are mapped straight from the kernel, aligned to 2 MiB and marked for
// transparent huge pages, so the kernel maps them 2 MiB at a time instead of faulting them
// in 4 KiB at a time: on the 1M-move scaffold page faults were 20-39 % of the cpu (issue 23).
// Smaller pieces, and every piece in sanitizer builds (so ASan still sees them), come from
// operator new.
#pragma once

#include <cstddef>
#include <vector>

namespace strand::slicer {

// Bytes from which a piece is mapped on its own (one huge page).
inline constexpr std::size_t kLargePieceBytes = std::size_t{2} << 20;

// Throws std::bad_alloc when the memory cannot be had.
void* large_allocate(std::size_t bytes);
// `bytes` as given to large_allocate.
void large_deallocate(void* p, std::size_t bytes) noexcept;
// False in sanitizer builds, where every piece comes from operator new.
bool large_pieces_mapped();

template <class T>
struct LargeAllocator {
  using value_type = T;
  LargeAllocator() = default;
  template <class U>
  LargeAllocator(const LargeAllocator<U>&) noexcept {}
  T* allocate(std::size_t n) { return static_cast<T*>(large_allocate(n * sizeof(T))); }
  void deallocate(T* p, std::size_t n) noexcept { large_deallocate(p, n * sizeof(T)); }
  template <class U>
  bool operator==(const LargeAllocator<U>&) const noexcept { return true; }
};

// A vector whose storage comes from large_allocate.
template <class T>
using LargeVector = std::vector<T, LargeAllocator<T>>;

}  // namespace strand::slicer
