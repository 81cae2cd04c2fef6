// SPDX-License-Identifier: MIT
// Raw storage for the library's large record arrays (the build's primitive
// records and node vector, the traversal's nodes, pairs and triangles),
// internal to the library. Arrays of a million-triangle scene span tens of
// MiB: on transparent huge pages they take far fewer first-touch page
// faults (the build) and TLB misses (incoherent rays).
#pragma once

#include <sys/mman.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>

namespace pluecker {

inline constexpr std::size_t kHugePage = std::size_t{2} << 20;

// Advises the whole 2 MiB pages inside [p, p + bytes) for transparent huge
// pages; meant for storage not yet touched. Advice only: failure is
// harmless.
inline void advise_huge(const void* p, std::size_t bytes) {
#if defined(MADV_HUGEPAGE)
    const auto lo = (reinterpret_cast<std::uintptr_t>(p) + kHugePage - 1) & ~(kHugePage - 1);
    const auto hi = (reinterpret_cast<std::uintptr_t>(p) + bytes) & ~(kHugePage - 1);
    if (hi > lo) madvise(reinterpret_cast<void*>(lo), hi - lo, MADV_HUGEPAGE);
#else
    (void)p;
    (void)bytes;
#endif
}

// Uninitialised storage for n records of T (at least one), 64-byte
// aligned; from 2 MiB on, 2 MiB aligned and advised for huge pages.
// Release with std::free (FreeRecords).
template <class T>
T* alloc_records(std::size_t n) {
    static_assert(alignof(T) <= 64);
    std::size_t bytes = std::max<std::size_t>(n, 1) * sizeof(T);
    const std::size_t align = bytes >= kHugePage ? kHugePage : 64;
    bytes = (bytes + align - 1) / align * align;
    void* p = std::aligned_alloc(align, bytes);
    if (!p) throw std::bad_alloc();
    if (align == kHugePage) advise_huge(p, bytes);
    return static_cast<T*>(p);
}

struct FreeRecords {
    void operator()(void* p) const { std::free(p); }
};

}  // namespace pluecker
