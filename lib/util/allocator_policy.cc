#include "lib/util/allocator_policy.h"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace lutex {

void MapLargeBlocksFromTheSystem() {
#if defined(__GLIBC__)
  // Setting the threshold also stops glibc from moving it.
  mallopt(M_MMAP_THRESHOLD, static_cast<int>(kLargeBlockBytes));
#endif
}

}  // namespace lutex
