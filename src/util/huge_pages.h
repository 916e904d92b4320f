// Memory for the large arrays that rays read at random (the wide BVH's nodes and leaf blocks).
// A tree of 10^7 triangles spans ~500 MB: in 4 KiB pages nearly every node a ray visits is
// also a TLB miss and a page walk, in 2 MiB pages the TLB covers gigabytes. Linux lends
// transparent huge pages to regions that ask for them (madvise(MADV_HUGEPAGE)) under its
// "madvise" policy, the default of many distributions, and only to 2 MiB-aligned ranges; Embree's
// allocator asks the same way. Arrays of 2 MiB or more get their own aligned mapping with that
// advice; smaller ones come from operator new, as with std::allocator.
#pragma once

#include <cstddef>
#include <new>

namespace wavetrace {

inline constexpr size_t kHugePageBytes = size_t(2) << 20;

// Storage of `bytes` aligned to `align` (a power of two), huge-page backed as above where the
// system lends it; throws std::bad_alloc. free_huge_pages takes the same bytes and align back.
void* allocate_huge_pages(size_t bytes, size_t align);
void free_huge_pages(void* p, size_t bytes, size_t align) noexcept;

template <class T>
struct HugePageAllocator {
    using value_type = T;
    HugePageAllocator() = default;
    template <class U>
    HugePageAllocator(const HugePageAllocator<U>&) noexcept {}
    T* allocate(size_t n) {
        return static_cast<T*>(allocate_huge_pages(n * sizeof(T), alignof(T)));
    }
    void deallocate(T* p, size_t n) noexcept { free_huge_pages(p, n * sizeof(T), alignof(T)); }
    template <class U>
    bool operator==(const HugePageAllocator<U>&) const noexcept {
        return true;
    }
};

}  // namespace wavetrace
