// The built-in thread pool: the task system of a world whose host brings
// no job system of its own (cloth_world_desc.worker_count > 1 and no
// enqueue_task callback).
//
// Written by hand rather than taken from a library because what the step
// needs is narrow and specific: one parallel_for at a time from one
// stepping thread, which also works (it is worker 0); dispatch that
// allocates nothing; stable worker indices for profiling; and a barrier
// that spins briefly (stages are tens of microseconds apart within a
// frame) before it sleeps (frames are milliseconds apart). The standard
// library has no pool; TBB or Taskflow would add a dependency and a second
// scheduler inside the host's engine for this one loop.
//
// Scheduling uses atomics (which range runs where); results never do:
// every sum in a stage is a fixed-order gather, so the bits do not depend
// on the schedule.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "jobs/task_system.h"

namespace cloth {

// cloth_world_set_worker_spin's default: half a millisecond. Workers poll
// through the gaps between stages and between a host's back-to-back steps,
// and at 60 steps a second polling costs each of them at most 3 % of a core.
constexpr uint32_t kDefaultSpinMicroseconds = 500;
constexpr uint32_t kMaxWorkerSpinMicroseconds = 1000000;

class ThreadPool final : public TaskSystem {
  public:
    // `workers` threads run tasks, the calling thread of parallel_for
    // among them; workers - 1 threads are started here (none for 0 or 1).
    explicit ThreadPool(uint32_t workers);
    ~ThreadPool() override;
    ThreadPool(const ThreadPool&) = delete;
    ThreadPool& operator=(const ThreadPool&) = delete;

    uint32_t worker_count() const override { return worker_count_; }
    // How long an idle worker polls for the next job before it sleeps.
    // Within a step the next stage comes microseconds later; the next step
    // is usually milliseconds away, and a worker woken from sleep costs the
    // step its wake-up and, on a busy machine, its core's cold caches.
    void set_spin(uint32_t microseconds) { spin_ns_.store(uint64_t{microseconds} * 1000u); }
    uint32_t spin() const { return static_cast<uint32_t>(spin_ns_.load() / 1000u); }
    void parallel_for(uint32_t count, uint32_t min_range, RangeTask task, void* context) override;

  private:
    struct Job {
        RangeTask task = nullptr;
        void* context = nullptr;
        uint32_t count = 0;
        uint32_t grain = 1;
    };
    void worker_main(uint32_t worker);
    // Runs ranges of the job of `epoch` until none is left.
    void run_ranges(uint32_t epoch, uint32_t worker);

    // A job's items are split into one contiguous block per worker. Worker
    // w takes ranges from block w first and then helps with the others, so
    // with balanced stages every worker touches the same particle groups in
    // every stage of a step (their data stays in its core's cache) while a
    // late worker's block is still taken over by the others.
    struct alignas(64) Block {
        // High 32 bits: epoch of the job; low 32 bits: next item of the
        // block to hand out. A range is taken by compare-and-swap within
        // one epoch, so a late worker never takes a range of a newer job.
        std::atomic<uint64_t> ticket{0};
    };

    uint32_t worker_count_;
    // Two job slots: the job of epoch e lives in slot e & 1 (with its block
    // ends), so a worker that is late for epoch e never reads a slot being
    // written for e + 1.
    Job jobs_[2];
    std::unique_ptr<uint32_t[]> block_ends_[2];  // per slot, per worker
    std::unique_ptr<Block[]> blocks_;            // per worker
    // High 32 bits: epoch of the current job (the low bits are unused).
    std::atomic<uint64_t> ticket_{0};
    std::atomic<uint32_t> done_{0};    // items of the current job finished
    std::atomic<uint32_t> inside_{0};  // workers between reading the ticket and leaving run_ranges
    std::atomic<uint32_t> sleepers_{0};
    std::atomic<uint64_t> spin_ns_{uint64_t{kDefaultSpinMicroseconds} * 1000u};
    std::atomic<bool> stop_{false};
    std::mutex mutex_;
    std::condition_variable wake_;
    std::vector<std::thread> threads_;
};

}  // namespace cloth
