#include "base/host_allocator.h"

#include <cstdlib>

namespace cloth {

void* HostMemory::allocate(size_t size, size_t alignment) const {
    if (alignment < alignof(std::max_align_t)) alignment = alignof(std::max_align_t);
    void* p = nullptr;
    if (alloc) {
        p = alloc(size, alignment, user);
    } else {
        // aligned_alloc needs a size that is a multiple of the alignment.
        p = std::aligned_alloc(alignment, (size + alignment - 1) / alignment * alignment);
    }
    if (!p) throw std::bad_alloc();
    return p;
}

void HostMemory::deallocate(void* ptr, size_t size) const {
    if (!ptr) return;
    if (free) {
        free(ptr, size, user);
    } else {
        std::free(ptr);
    }
}

}  // namespace cloth
