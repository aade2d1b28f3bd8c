// glibc's malloc_trim, where available.
#include "slicer/memory.h"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace strand::slicer {

void release_free_memory() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

}  // namespace strand::slicer
