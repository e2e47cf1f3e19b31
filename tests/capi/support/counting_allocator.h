// The host callbacks every C API test gives a world: an allocator that
// counts blocks and bytes, checks each free against what it handed out,
// and can be told to fail; and a log that records what the world reports.
// One object holds both, since a world passes one `user` pointer to its
// alloc, free and log. Used by the C API contract tests, the soak and the
// fuzzer (header-only; it depends on nothing but cloth.h).
//
// The block table allocates with malloc, not operator new, so a program
// that counts C++ heap allocations (the soak) sees none of the
// allocator's own bookkeeping. A world calls its callbacks on the thread
// that made the API call, one call at a time (cloth.h, threading
// contract), so the allocator takes no lock.
#pragma once

#include <cloth/cloth.h>
#ifdef _WIN32
#include <malloc.h>
#endif

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <map>
#include <new>
#include <string>
#include <utility>
#include <vector>

namespace cloth_test {

// An STL allocator on malloc (keeps the block table off operator new).
template <typename T>
struct MallocAllocator {
    using value_type = T;
    MallocAllocator() = default;
    template <typename U>
    MallocAllocator(const MallocAllocator<U>&) noexcept {}
    T* allocate(size_t n) {
        if (void* p = std::malloc(n * sizeof(T))) return static_cast<T*>(p);
        throw std::bad_alloc();
    }
    void deallocate(T* p, size_t) noexcept { std::free(p); }
    template <typename U>
    bool operator==(const MallocAllocator<U>&) const noexcept {
        return true;
    }
    template <typename U>
    bool operator!=(const MallocAllocator<U>&) const noexcept {
        return false;
    }
};

struct LogEntry {
    cloth_log_level level;
    cloth_result code;
    std::string message;
};

class CountingAllocator {
  public:
    // What to do when the library misuses a callback (a bad alignment, a free
    // of a block it was not given, a wrong size, a NULL or empty message, an
    // unknown log level, a `user` pointer that is not this object). Unset:
    // the misuse is recorded in violations() (wrong_user_pointers() for the
    // last one). The fuzzer sets a handler that aborts.
    using ViolationHandler = void (*)(const char* what);
    static ViolationHandler& violation_handler() {
        static ViolationHandler handler = nullptr;
        return handler;
    }
    // Callbacks that received a `user` pointer that is not a CountingAllocator.
    static std::atomic<int>& wrong_user_pointers() {
        static std::atomic<int> count{0};
        return count;
    }

    CountingAllocator() = default;
    CountingAllocator(const CountingAllocator&) = delete;
    CountingAllocator& operator=(const CountingAllocator&) = delete;
    ~CountingAllocator() { magic_ = 0; }

    // Makes a world description use this allocator, its log, or both.
    void use_for_memory(cloth_world_desc& desc) {
        desc.alloc = &CountingAllocator::alloc;
        desc.free = &CountingAllocator::free;
        desc.user = this;
    }
    void use_for_log(cloth_world_desc& desc) {
        desc.log = &CountingAllocator::log;
        desc.user = this;
    }
    cloth_world_desc world_desc() {
        cloth_world_desc desc = cloth_default_world_desc();
        use_for_memory(desc);
        use_for_log(desc);
        return desc;
    }

    // The next `n` allocations succeed, then every one fails; < 0: none fails.
    void fail_after(long n) { allocations_left_ = n; }
    // Larger single requests fail (a host with bounded memory).
    void set_max_single_allocation(size_t bytes) { max_single_allocation_ = bytes; }

    size_t live_bytes() const { return live_bytes_; }
    size_t live_blocks() const { return blocks_.size(); }
    size_t peak_bytes() const { return peak_bytes_; }
    uint64_t allocations() const { return allocations_; }  // requests that returned memory
    uint64_t frees() const { return frees_; }
    uint64_t refusals() const { return refusals_; }  // requests answered with NULL

    const std::vector<LogEntry>& logs() const { return logs_; }
    void clear_logs() { logs_.clear(); }
    // Log entries of level CLOTH_LOG_ERROR from index `first` on.
    std::vector<LogEntry> errors_since(size_t first) const {
        std::vector<LogEntry> out;
        for (size_t i = first; i < logs_.size(); ++i)
            if (logs_[i].level == CLOTH_LOG_ERROR) out.push_back(logs_[i]);
        return out;
    }

    const std::vector<std::string>& violations() const { return violations_; }

    static void* alloc(size_t size, size_t alignment, void* user) {
        CountingAllocator* self = from_user(user);
        if (self == nullptr) return nullptr;
        if (alignment == 0 || (alignment & (alignment - 1)) != 0 || alignment > 64) {
            self->violation("alloc with alignment " + std::to_string(alignment));
            return nullptr;
        }
        if (self->allocations_left_ == 0 || size > self->max_single_allocation_) {
            ++self->refusals_;
            return nullptr;
        }
        // posix_memalign of exactly `size` bytes: AddressSanitizer sees a
        // read or write one byte past the block.
        // Windows' C runtimes have no posix_memalign: _aligned_malloc, whose
        // blocks only _aligned_free takes back.
        void* p = nullptr;
#ifdef _WIN32
        p = _aligned_malloc(size == 0 ? 1 : size, alignment);
        if (p == nullptr) {
#else
        if (posix_memalign(&p, alignment < sizeof(void*) ? sizeof(void*) : alignment, size == 0 ? 1 : size) !=
            0) {
#endif
            ++self->refusals_;
            return nullptr;
        }
        if (self->allocations_left_ > 0) --self->allocations_left_;
        self->blocks_[p] = size;
        self->live_bytes_ += size;
        if (self->live_bytes_ > self->peak_bytes_) self->peak_bytes_ = self->live_bytes_;
        ++self->allocations_;
        return p;
    }

    static void free(void* ptr, size_t size, void* user) {
        CountingAllocator* self = from_user(user);
        if (self == nullptr) return;
        if (ptr == nullptr) {
            self->violation("free(NULL)");
            return;
        }
        const auto it = self->blocks_.find(ptr);
        if (it == self->blocks_.end()) {
            self->violation("free of a pointer the allocator did not return (or freed twice)");
            return;
        }
        if (it->second != size) {
            self->violation("free size " + std::to_string(size) + " for a block of " +
                            std::to_string(it->second));
        }
        self->live_bytes_ -= it->second;
        self->blocks_.erase(it);
        ++self->frees_;
#ifdef _WIN32
        _aligned_free(ptr);
#else
        std::free(ptr);
#endif
    }

    static void log(cloth_log_level level, cloth_result code, const char* message, void* user) {
        CountingAllocator* self = from_user(user);
        if (self == nullptr) return;
        if (level != CLOTH_LOG_ERROR && level != CLOTH_LOG_WARNING && level != CLOTH_LOG_INFO)
            self->violation("log with an unknown level " + std::to_string(static_cast<int>(level)));
        if (message == nullptr || *message == '\0') {
            self->violation(message == nullptr ? "log with a NULL message" : "log with an empty message");
            return;
        }
        self->logs_.push_back({level, code, message});
    }

  private:
    static constexpr uint32_t kMagic = 0xC107'4057u;

    static CountingAllocator* from_user(void* user) {
        CountingAllocator* self = static_cast<CountingAllocator*>(user);
        if (self == nullptr || self->magic_ != kMagic) {
            ++wrong_user_pointers();
            if (violation_handler()) violation_handler()("a callback's user pointer is not desc.user");
            return nullptr;
        }
        return self;
    }

    void violation(const std::string& what) {
        if (violation_handler()) violation_handler()(what.c_str());
        violations_.push_back(what);
    }

    uint32_t magic_ = kMagic;
    std::map<void*, size_t, std::less<void*>, MallocAllocator<std::pair<void* const, size_t>>> blocks_;
    size_t live_bytes_ = 0;
    size_t peak_bytes_ = 0;
    uint64_t allocations_ = 0;
    uint64_t frees_ = 0;
    uint64_t refusals_ = 0;
    long allocations_left_ = -1;
    size_t max_single_allocation_ = size_t{256} << 20;
    std::vector<LogEntry> logs_;
    std::vector<std::string> violations_;
};

}  // namespace cloth_test
