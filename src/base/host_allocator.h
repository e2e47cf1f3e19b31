// Every byte the library keeps goes through the host's allocator callbacks
// (cloth_world_desc.alloc/free). HostVector<T> is std::vector routed there.
// An allocator returning NULL throws std::bad_alloc, which the C API turns
// into CLOTH_ERROR_OUT_OF_MEMORY; the throwing call has changed nothing.
#pragma once

#include <cstddef>
#include <memory>
#include <new>
#include <vector>

namespace cloth {

struct HostMemory {
    void* (*alloc)(size_t size, size_t alignment, void* user) = nullptr;
    void (*free)(void* ptr, size_t size, void* user) = nullptr;
    void* user = nullptr;

    void* allocate(size_t size, size_t alignment) const;
    void deallocate(void* ptr, size_t size) const;
};

template <class T>
class HostAllocator {
  public:
    using value_type = T;

    explicit HostAllocator(const HostMemory* memory) noexcept : memory_(memory) {}
    template <class U>
    HostAllocator(const HostAllocator<U>& other) noexcept : memory_(other.memory()) {}

    T* allocate(size_t n) {
        if (n > static_cast<size_t>(-1) / sizeof(T)) throw std::bad_alloc();
        return static_cast<T*>(memory_->allocate(n * sizeof(T), alignof(T)));
    }
    void deallocate(T* p, size_t n) noexcept { memory_->deallocate(p, n * sizeof(T)); }

    const HostMemory* memory() const noexcept { return memory_; }

    template <class U>
    bool operator==(const HostAllocator<U>& o) const noexcept {
        return memory_ == o.memory();
    }
    template <class U>
    bool operator!=(const HostAllocator<U>& o) const noexcept {
        return memory_ != o.memory();
    }

  private:
    const HostMemory* memory_;
};

template <class T>
using HostVector = std::vector<T, HostAllocator<T>>;

}  // namespace cloth
