// A small buffer that ends where readable memory ends: the page after it is
// mapped without access, so a call that reads one byte past the buffer
// crashes at once, in any build. For the tests that a count above its
// limit is refused before the buffer it sizes is read.
#pragma once

#ifdef _WIN32
#ifndef NOMINMAX
#define NOMINMAX
#endif
#ifndef WIN32_LEAN_AND_MEAN
#define WIN32_LEAN_AND_MEAN
#endif
#include <windows.h>
#else
#include <sys/mman.h>
#include <unistd.h>
#endif

#include <cstddef>
#include <cstring>

namespace cloth_test {

class GuardedBuffer {
  public:
    // `bytes` readable bytes (at most a page), a copy of `contents`.
    GuardedBuffer(const void* contents, size_t bytes) : page_(page_size()) {
#ifdef _WIN32
        void* map = ::VirtualAlloc(nullptr, 2 * page_, MEM_RESERVE | MEM_COMMIT, PAGE_READWRITE);
        if (map == nullptr) return;
        map_ = static_cast<unsigned char*>(map);
        DWORD old_protection = 0;
        ::VirtualProtect(map_ + page_, page_, PAGE_NOACCESS, &old_protection);
#else
        void* map = ::mmap(nullptr, 2 * page_, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        if (map == MAP_FAILED) return;
        map_ = static_cast<unsigned char*>(map);
        ::mprotect(map_ + page_, page_, PROT_NONE);
#endif
        data_ = map_ + page_ - bytes;
        std::memcpy(data_, contents, bytes);
    }
    ~GuardedBuffer() {
#ifdef _WIN32
        if (map_) ::VirtualFree(map_, 0, MEM_RELEASE);
#else
        if (map_) ::munmap(map_, 2 * page_);
#endif
    }
    GuardedBuffer(const GuardedBuffer&) = delete;
    GuardedBuffer& operator=(const GuardedBuffer&) = delete;

    template <typename T>
    const T* as() const {
        return reinterpret_cast<const T*>(data_);
    }
    bool ok() const { return data_ != nullptr; }

  private:
    static size_t page_size() {
#ifdef _WIN32
        SYSTEM_INFO info;
        ::GetSystemInfo(&info);
        return info.dwPageSize;
#else
        return static_cast<size_t>(::sysconf(_SC_PAGESIZE));
#endif
    }

    size_t page_;
    unsigned char* map_ = nullptr;
    unsigned char* data_ = nullptr;
};

}  // namespace cloth_test
