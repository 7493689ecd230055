// back_with_huge_pages (raylab/bvh.h): the BVH's and the scene's large arrays on 2 MiB
// pages.
#include <cstdint>

#include "raylab/bvh.h"

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace raylab {

bool back_with_huge_pages(const void* data, size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    if (bytes < kHugePagesFrom) return false;
    // The huge pages wholly inside the array: the pages around it may hold other data
    constexpr std::uintptr_t kPage = std::uintptr_t{2} << 20;
    const std::uintptr_t begin = reinterpret_cast<std::uintptr_t>(data);
    const std::uintptr_t first = (begin + kPage - 1) & ~(kPage - 1);
    const std::uintptr_t last = (begin + bytes) & ~(kPage - 1);
    if (last <= first) return false;
    void* const range = reinterpret_cast<void*>(first);
    // MADV_HUGEPAGE: later faults and khugepaged give the range huge pages. MADV_COLLAPSE
    // (25; Linux 6.1, not in every libc's headers) collapses the pages already there
    constexpr int kMadvCollapse = 25;
    if (madvise(range, last - first, MADV_HUGEPAGE) != 0) return false;
    return madvise(range, last - first, kMadvCollapse) == 0;
#else
    (void)data;
    (void)bytes;
    return false;
#endif
}

}  // namespace raylab
