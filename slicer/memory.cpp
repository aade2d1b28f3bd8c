// glibc's malloc_trim, where available.
#include "slicer/memory.h"

#include <cstdlib>  // defines __GLIBC__ on glibc systems, tested below

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
