#include "util/huge_pages.h"

#include <sys/mman.h>

#include <algorithm>
#include <cstdint>

namespace wavetrace {
namespace {

size_t whole_huge_pages(size_t bytes) {
    return (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
}

std::align_val_t new_alignment(size_t align) {
    return std::align_val_t(std::max(align, size_t(__STDCPP_DEFAULT_NEW_ALIGNMENT__)));
}

}  // namespace

void* allocate_huge_pages(size_t bytes, size_t align) {
    if (bytes < kHugePageBytes) return ::operator new(bytes, new_alignment(align));
    // Map one huge page more than needed and unmap what lies outside the first aligned range.
    const size_t size = whole_huge_pages(bytes);
    void* mapped = mmap(nullptr, size + kHugePageBytes, PROT_READ | PROT_WRITE,
                        MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (mapped == MAP_FAILED) throw std::bad_alloc();
    const uintptr_t start = reinterpret_cast<uintptr_t>(mapped);
    const uintptr_t aligned = (start + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
    if (aligned > start) munmap(mapped, aligned - start);
    const uintptr_t end = start + size + kHugePageBytes;
    if (end > aligned + size) munmap(reinterpret_cast<void*>(aligned + size), end - aligned - size);
    void* p = reinterpret_cast<void*>(aligned);
    // Advice only: where the kernel has no huge pages to lend, the range stays in small pages.
    madvise(p, size, MADV_HUGEPAGE);
    return p;
}

void free_huge_pages(void* p, size_t bytes, size_t align) noexcept {
    if (p == nullptr) return;
    if (bytes < kHugePageBytes) {
        ::operator delete(p, new_alignment(align));
        return;
    }
    munmap(p, whole_huge_pages(bytes));
}

}  // namespace wavetrace
