// back_with_huge_pages (raylab/engine.h), which the engine asks for the BVH's and the
// scene's large arrays: only the array's whole huge pages are advised, and the data is
// unchanged, whether the kernel grants them or not.
#include <doctest/doctest.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <sys/mman.h>

#include "raylab/engine.h"

using namespace raylab;

namespace {

// A mapping of /proc/self/smaps: its range, its AnonHugePages and whether its VmFlags
// hold hg (MADV_HUGEPAGE)
struct Mapping {
    std::uintptr_t lo = 0, hi = 0;
    long huge_kib = 0;
    bool advised = false;
};

std::vector<Mapping> smaps() {
    std::ifstream in("/proc/self/smaps");
    std::vector<Mapping> maps;
    for (std::string line; std::getline(in, line);) {
        unsigned long lo = 0, hi = 0;
        long kib = 0;
        if (std::sscanf(line.c_str(), "%lx-%lx ", &lo, &hi) == 2) {
            maps.push_back({lo, hi, 0, false});
        } else if (!maps.empty() &&
                   std::sscanf(line.c_str(), "AnonHugePages: %ld kB", &kib) == 1) {
            maps.back().huge_kib = kib;
        } else if (!maps.empty() && line.rfind("VmFlags:", 0) == 0) {
            maps.back().advised = (line + " ").find(" hg ") != std::string::npos;
        }
    }
    return maps;
}

// The huge pages, in KiB, of the mappings that overlap [lo, hi)
long huge_kib_over(const std::vector<Mapping>& maps, std::uintptr_t lo,
                   std::uintptr_t hi) {
    long kib = 0;
    for (const Mapping& m : maps)
        kib += m.lo < hi && lo < m.hi ? m.huge_kib : 0;
    return kib;
}

}  // namespace

TEST_SUITE("huge pages") {
    TEST_CASE("huge pages for large arrays leave the data as it was") {
        std::ifstream size_file("/sys/kernel/mm/transparent_hugepage/hpage_pmd_size");
        std::uintptr_t page = 0;
        if (!(size_file >> page) || page == 0 || smaps().empty()) {
            MESSAGE("no transparent huge pages or no /proc/self/smaps here: skipped");
            return;
        }
        // An array of 8 huge pages less 20 KiB, starting 12 KiB into a mapping that
        // opts out of huge pages before it is written: only what the call asks for can
        // be huge afterwards, in the kernel's "always" mode too
        const size_t bytes = 8 * page - 20480;
        const size_t length = 10 * page;
        void* const map = mmap(nullptr, length, PROT_READ | PROT_WRITE,
                               MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        REQUIRE(map != MAP_FAILED);
        REQUIRE(madvise(map, length, MADV_NOHUGEPAGE) == 0);
        const std::uintptr_t base =
            (reinterpret_cast<std::uintptr_t>(map) + page - 1) & ~(page - 1);
        auto* const data = reinterpret_cast<std::uint32_t*>(base + 12288);
        const size_t n = bytes / sizeof(std::uint32_t);
        for (size_t k = 0; k < n; ++k)
            data[k] = static_cast<std::uint32_t>(k * 2654435761u);
        const std::uintptr_t begin = reinterpret_cast<std::uintptr_t>(data);
        const std::uintptr_t first = (begin + page - 1) & ~(page - 1);
        const std::uintptr_t last = (begin + bytes) & ~(page - 1);
        REQUIRE(last - first == 6 * page);
        CHECK(huge_kib_over(smaps(), begin, begin + bytes) == 0);

        const bool collapsed = back_with_huge_pages(data, bytes);
        size_t wrong = 0;
        for (size_t k = 0; k < n; ++k)
            wrong += data[k] != static_cast<std::uint32_t>(k * 2654435761u);
        CHECK(wrong == 0);
        const std::vector<Mapping> maps = smaps();
        const long kib = huge_kib_over(maps, begin, begin + bytes);
        INFO("huge KiB over the array: " << kib << ", collapsed: " << collapsed);
        if (collapsed) {
            // The six whole pages inside, and nothing else
            CHECK(kib == static_cast<long>(6 * page / 1024));
        } else {
            MESSAGE(
                "the kernel declined huge pages here (no MADV_COLLAPSE before Linux "
                "6.1, or short of memory); only the data was checked");
        }
        // The advice stays inside the array's whole pages
        for (const Mapping& m : maps) {
            if (m.advised && m.lo < begin + bytes && begin < m.hi) {
                CHECK(m.lo >= first);
                CHECK(m.hi <= last);
            }
        }
        munmap(map, length);
        // Below kHugePagesFrom nothing is asked
        std::vector<std::uint32_t> small(kHugePagesFrom / sizeof(std::uint32_t) - 1);
        CHECK_FALSE(back_with_huge_pages(small.data(), small.size() * sizeof(small[0])));
    }
}
