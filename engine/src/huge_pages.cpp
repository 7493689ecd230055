// back_with_huge_pages (raylab/engine.h): the BVH's and the scene's large arrays on huge
// pages.
#include <cerrno>
#include <cstdint>
#include <fstream>

#include "raylab/engine.h"

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace raylab {

namespace {

// The size of the kernel's transparent huge page (2 MiB on x86-64; 32 or 512 MiB on
// arm64 kernels with 16 or 64 KiB pages), read once; 0 when the kernel has none
std::uintptr_t huge_page_size() {
    static const std::uintptr_t size = [] {
        std::ifstream in("/sys/kernel/mm/transparent_hugepage/hpage_pmd_size");
        unsigned long long bytes = 0;
        if (!(in >> bytes)) return std::uintptr_t{0};
        // A power of two, or none
        return bytes != 0 && (bytes & (bytes - 1)) == 0 ? std::uintptr_t(bytes)
                                                        : std::uintptr_t{0};
    }();
    return size;
}

}  // namespace

bool back_with_huge_pages(const void* data, size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    if (bytes < kHugePagesFrom) return false;
    const std::uintptr_t page = huge_page_size();
    if (page == 0) return false;
    // The huge pages wholly inside the array: the pages around it may hold other data
    const std::uintptr_t begin = reinterpret_cast<std::uintptr_t>(data);
    const std::uintptr_t first = (begin + page - 1) & ~(page - 1);
    const std::uintptr_t last = (begin + bytes) & ~(page - 1);
    if (last <= first) return false;
    void* const range = reinterpret_cast<void*>(first);
    // MADV_HUGEPAGE: later faults and khugepaged give the range huge pages. MADV_COLLAPSE
    // (Linux 6.1; 25 where the libc's headers lack it) collapses the pages already there
#ifdef MADV_COLLAPSE
    constexpr int kMadvCollapse = MADV_COLLAPSE;
#else
    constexpr int kMadvCollapse = 25;
#endif
    if (madvise(range, last - first, MADV_HUGEPAGE) != 0) return false;
    // EAGAIN: a page was busy for a moment (the kernel's own tests retry it)
    for (int attempt = 0; attempt < 3; ++attempt) {
        if (madvise(range, last - first, kMadvCollapse) == 0) return true;
        if (errno != EAGAIN) return false;
    }
    return false;
#else
    (void)data;
    (void)bytes;
    return false;
#endif
}

}  // namespace raylab
