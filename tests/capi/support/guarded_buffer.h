// A small buffer that ends where readable memory ends: the page after it is
// mapped without access, so a call that reads one byte past the buffer
// crashes at once, in any build. For the tests that a count above its
// limit is refused before the buffer it sizes is read.
#pragma once

#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <cstring>

namespace cloth_test {

class GuardedBuffer {
  public:
    // `bytes` readable bytes (at most a page), a copy of `contents`.
    GuardedBuffer(const void* contents, size_t bytes) : page_(static_cast<size_t>(::sysconf(_SC_PAGESIZE))) {
        void* map = ::mmap(nullptr, 2 * page_, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        if (map == MAP_FAILED) return;
        map_ = static_cast<unsigned char*>(map);
        ::mprotect(map_ + page_, page_, PROT_NONE);
        data_ = map_ + page_ - bytes;
        std::memcpy(data_, contents, bytes);
    }
    ~GuardedBuffer() {
        if (map_) ::munmap(map_, 2 * page_);
    }
    GuardedBuffer(const GuardedBuffer&) = delete;
    GuardedBuffer& operator=(const GuardedBuffer&) = delete;

    template <typename T>
    const T* as() const {
        return reinterpret_cast<const T*>(data_);
    }
    bool ok() const { return data_ != nullptr; }

  private:
    size_t page_;
    unsigned char* map_ = nullptr;
    unsigned char* data_ = nullptr;
};

}  // namespace cloth_test
