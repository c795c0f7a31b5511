#include "petroscope/core/heap.hpp"

#ifdef __GLIBC__
#include <malloc.h>
#endif

namespace petroscope {

void keep_large_blocks_in_heap() {
#ifdef __GLIBC__
    mallopt(M_MMAP_THRESHOLD, 32 << 20);
    mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
}

}  // namespace petroscope
