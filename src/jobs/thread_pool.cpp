// The built-in pool (why it is written by hand: thread_pool.h).
//
// Protocol. The stepping thread publishes a job by writing its slot, the
// block tickets (new epoch, the block's first item) and then the ticket
// (new epoch); workers see the epoch change, take ranges by
// compare-and-swap on the block tickets (their own block first) and count
// finished items in done_; the stepping thread takes ranges too and
// returns once done_ reaches the item count. Before it writes a slot it
// waits until no worker is inside a job (inside_), so a late worker never
// reads a slot while it is written.
#include "jobs/thread_pool.h"

#include <algorithm>
#include <chrono>

namespace cloth {
namespace {

inline void cpu_pause() {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
}

// Pause instructions between two clock reads of a polling worker (a read
// costs about three pauses).
constexpr uint32_t kPausesPerClockRead = 32;
// Spin iterations of a waiting stepping thread before it yields its core
// (the machine may have fewer cores than workers).
constexpr uint32_t kSpinBeforeYield = 1u << 10;

inline uint32_t epoch_of(uint64_t ticket) { return static_cast<uint32_t>(ticket >> 32); }

template <class Done>
void wait_until(Done done) {
    for (uint32_t spin = 0; !done(); ++spin) {
        if (spin < kSpinBeforeYield) {
            cpu_pause();
        } else {
            std::this_thread::yield();
        }
    }
}

}  // namespace

ThreadPool::ThreadPool(uint32_t workers)
    : worker_count_(std::max(1u, workers)),
      block_ends_{std::make_unique<uint32_t[]>(worker_count_), std::make_unique<uint32_t[]>(worker_count_)},
      blocks_(std::make_unique<Block[]>(worker_count_)) {
    threads_.reserve(worker_count_ - 1);
    for (uint32_t w = 1; w < worker_count_; ++w) threads_.emplace_back([this, w] { worker_main(w); });
}

ThreadPool::~ThreadPool() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stop_.store(true);
    }
    wake_.notify_all();
    for (std::thread& t : threads_) t.join();
}

void ThreadPool::parallel_for(uint32_t count, uint32_t min_range, RangeTask task, void* context) {
    if (count == 0) return;
    min_range = std::max(1u, min_range);
    if (worker_count_ == 1 || count <= min_range) {
        task(0, count, 0, context);
        return;
    }
    wait_until([&] { return inside_.load() == 0; });
    const uint32_t epoch = epoch_of(ticket_.load()) + 1;
    // About four ranges per worker: enough to balance uneven groups.
    const uint32_t grain = std::max(min_range, count / (4 * worker_count_));
    const uint32_t ranges = (count + grain - 1) / grain;
    jobs_[epoch & 1] = Job{task, context, count, grain};
    uint32_t* ends = block_ends_[epoch & 1].get();
    for (uint32_t w = 0; w < worker_count_; ++w) {
        const uint64_t first_range = static_cast<uint64_t>(ranges) * w / worker_count_;
        const uint64_t end_range = static_cast<uint64_t>(ranges) * (w + 1) / worker_count_;
        ends[w] = static_cast<uint32_t>(std::min<uint64_t>(count, end_range * grain));
        const uint32_t first = static_cast<uint32_t>(std::min<uint64_t>(count, first_range * grain));
        blocks_[w].ticket.store((static_cast<uint64_t>(epoch) << 32) | first, std::memory_order_relaxed);
    }
    done_.store(0);
    ticket_.store(static_cast<uint64_t>(epoch) << 32);  // publishes the slot and the blocks
    if (sleepers_.load() > 0) {
        { std::lock_guard<std::mutex> lock(mutex_); }
        wake_.notify_all();
    }
    run_ranges(epoch, 0);
    wait_until([&] { return done_.load(std::memory_order_acquire) >= count; });
}

void ThreadPool::run_ranges(uint32_t epoch, uint32_t worker) {
    const Job job = jobs_[epoch & 1];
    const uint32_t* ends = block_ends_[epoch & 1].get();
    for (uint32_t k = 0; k < worker_count_; ++k) {
        const uint32_t b = (worker + k) % worker_count_;  // own block first
        std::atomic<uint64_t>& block = blocks_[b].ticket;
        uint64_t ticket = block.load();
        for (;;) {
            if (epoch_of(ticket) != epoch) return;  // a newer job: this one is done
            const uint32_t begin = static_cast<uint32_t>(ticket);
            if (begin >= ends[b]) break;
            const uint32_t end = std::min(ends[b], begin + job.grain);
            if (!block.compare_exchange_weak(ticket, (static_cast<uint64_t>(epoch) << 32) | end)) continue;
            job.task(begin, end, worker, job.context);
            done_.fetch_add(end - begin, std::memory_order_release);
            ticket = block.load();
        }
    }
}

void ThreadPool::worker_main(uint32_t worker) {
    uint32_t seen = 0;
    auto has_work = [&] { return stop_.load() || epoch_of(ticket_.load()) != seen; };
    for (;;) {
        // Poll for spin_ns_ after the last job, then sleep.
        const auto spin = std::chrono::nanoseconds(spin_ns_.load(std::memory_order_relaxed));
        const auto idle_since = std::chrono::steady_clock::now();
        for (uint32_t pauses = 1; !has_work(); ++pauses) {
            cpu_pause();
            if (pauses % kPausesPerClockRead == 0 && std::chrono::steady_clock::now() - idle_since >= spin)
                break;
        }
        if (!has_work()) {
            std::unique_lock<std::mutex> lock(mutex_);
            sleepers_.fetch_add(1);
            wake_.wait(lock, has_work);
            sleepers_.fetch_sub(1);
        }
        if (stop_.load()) return;
        inside_.fetch_add(1);
        const uint32_t epoch = epoch_of(ticket_.load());
        if (epoch != seen) {
            seen = epoch;
            run_ranges(epoch, worker);
        }
        inside_.fetch_sub(1);
    }
}

}  // namespace cloth
