// SPDX-License-Identifier: MIT
// An allocator for the lattice's per-cell arrays: blocks of 2 MiB or more are aligned to 2 MiB and marked
// for transparent huge pages (Linux madvise) before anything touches them. The free-surface passes and the
// cells gathered one by one read the 19 population arrays at scattered cells, 19 pages per cell: with
// 4 KiB pages nearly every such read also misses the TLB (docs/lbm.md, "Data layout"). Where the kernel
// does not grant huge pages the arrays are ordinary memory, only slower.
#pragma once
#include <cstddef>
#include <cstdlib>
#include <new>
#include <vector>
#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace sabo {

template <class T>
struct HugePageAllocator {
    using value_type = T;
    static constexpr std::size_t huge_page = std::size_t{2} << 20;

    HugePageAllocator() = default;
    template <class U>
    explicit HugePageAllocator(const HugePageAllocator<U>& /*other*/) noexcept {}

    [[nodiscard]] T* allocate(std::size_t n) {
        const std::size_t bytes = n * sizeof(T);
        if (bytes < huge_page) return static_cast<T*>(::operator new(bytes));
        const std::size_t rounded = (bytes + huge_page - 1) / huge_page * huge_page;
        void* p = std::aligned_alloc(huge_page, rounded);
        if (p == nullptr) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
        madvise(p, rounded, MADV_HUGEPAGE);  // a hint: refused, the pages are small ones
#endif
        return static_cast<T*>(p);
    }
    void deallocate(T* p, std::size_t n) noexcept {
        if (n * sizeof(T) < huge_page)
            ::operator delete(p);
        else
            std::free(p);
    }
    friend bool operator==(const HugePageAllocator& /*a*/, const HugePageAllocator& /*b*/) {
        return true;
    }
};

template <class T>
using HugePageVector = std::vector<T, HugePageAllocator<T>>;

}  // namespace sabo
