// The task seam: how the step hands its work to threads.
//
// A stage of the step is a loop over items (particle groups, one cloth's
// or many cloths'). The step calls parallel_for(count, min_range, task,
// context) once per stage; the task system runs task(begin, end, worker,
// context) over disjoint ranges covering [0, count), each at least
// min_range items long (except a final remainder), and returns when all
// have finished: that return is the barrier between stages. Nothing the
// step computes depends on how the items were split or on which worker
// ran them (every sum is a fixed-order gather), so any implementation
// gives the same bits:
//   SerialTasks      the calling thread, one range (no threads at all);
//   ThreadPool       the built-in pool (thread_pool.h);
//   HostTasks        the host engine's job system, through the
//                    enqueue/finish callbacks of cloth_world_desc.
// `worker` is in [0, worker_count()); a range task may use it to index
// per-worker scratch or profiling slots, never to decide a result.
#pragma once

#include <cstdint>

namespace cloth {

using RangeTask = void (*)(uint32_t begin, uint32_t end, uint32_t worker, void* context);

class TaskSystem {
  public:
    virtual ~TaskSystem() = default;
    // Workers that may run ranges (indices 0 .. worker_count() - 1).
    virtual uint32_t worker_count() const = 0;
    // Run `task` over [0, count) and return when every range has run.
    virtual void parallel_for(uint32_t count, uint32_t min_range, RangeTask task, void* context) = 0;
};

// Everything on the calling thread, as worker 0.
class SerialTasks final : public TaskSystem {
  public:
    uint32_t worker_count() const override { return 1; }
    void parallel_for(uint32_t count, uint32_t, RangeTask task, void* context) override {
        if (count > 0) task(0, count, 0, context);
    }
};

// parallel_for with a callable fn(begin, end, worker).
template <class Fn>
void parallel_for(TaskSystem& tasks, uint32_t count, uint32_t min_range, Fn& fn) {
    tasks.parallel_for(
        count, min_range,
        [](uint32_t begin, uint32_t end, uint32_t worker, void* context) {
            (*static_cast<Fn*>(context))(begin, end, worker);
        },
        &fn);
}

}  // namespace cloth
