#include "base/host_allocator.h"

#include <cstdlib>
#if defined(_WIN32)
#include <malloc.h>
#endif

namespace cloth {

void* HostMemory::allocate(size_t size, size_t alignment) const {
    if (alignment < alignof(std::max_align_t)) alignment = alignof(std::max_align_t);
    void* p = nullptr;
    if (alloc) {
        p = alloc(size, alignment, user);
    } else {
#if defined(_WIN32)
        // The Windows C runtimes have no aligned_alloc (its blocks cannot be
        // released with free); _aligned_malloc's are released with _aligned_free.
        p = _aligned_malloc(size, alignment);
#else
        // aligned_alloc needs a size that is a multiple of the alignment.
        p = std::aligned_alloc(alignment, (size + alignment - 1) / alignment * alignment);
#endif
    }
    if (!p) throw std::bad_alloc();
    return p;
}

void HostMemory::deallocate(void* ptr, size_t size) const {
    if (!ptr) return;
    if (free) {
        free(ptr, size, user);
    } else {
#if defined(_WIN32)
        _aligned_free(ptr);
#else
        std::free(ptr);
#endif
    }
}

}  // namespace cloth
