// Determinism by construction: a wind-blown flag stepped 300 times (40 in
// sanitized builds) ends in
// the same bits, hashed, whatever runs the step's tasks: the calling
// thread, the built-in pool with 2, 3, 4 or 8 workers, or a host engine's
// job system (implemented below, as an engine would, with its own threads).
#include <gtest/gtest.h>

#include <atomic>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <mutex>
#include <thread>
#include <vector>

#include "scenes.h"

namespace {

using cloth_samples::Scene;
using cloth_samples::SceneConfig;
using cloth_samples::SceneKind;

// A small job system of the kind an engine has: a fixed set of threads
// taking jobs from a queue. enqueue_task splits the task into ranges of
// min_range items and queues them; finish_task helps run queued ranges on
// the calling thread (worker 0) until its task is complete.
class HostJobSystem {
  public:
    static constexpr uint32_t kThreads = 3;
    static constexpr uint32_t kWorkers = kThreads + 1;

    HostJobSystem() {
        for (uint32_t t = 0; t < kThreads; ++t) threads_.emplace_back([this, t] { run(t + 1); });
    }
    ~HostJobSystem() {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            stop_ = true;
        }
        wake_.notify_all();
        for (std::thread& t : threads_) t.join();
    }

    // A world description that steps on this job system.
    cloth_world_desc world_desc() {
        cloth_world_desc desc = cloth_default_world_desc();
        desc.worker_count = kWorkers;
        desc.enqueue_task = &HostJobSystem::enqueue;
        desc.finish_task = &HostJobSystem::finish;
        desc.task_user = this;
        return desc;
    }

    static void* enqueue(cloth_task_fn* task, uint32_t count, uint32_t min_range, void* context, void* user) {
        auto* self = static_cast<HostJobSystem*>(user);
        ++self->enqueued;
        if (count <= min_range) {  // engines run tiny tasks inline
            task(0, count, 0, context);
            return nullptr;
        }
        auto* job = new Job{task, context, {}};
        {
            std::lock_guard<std::mutex> lock(self->mutex_);
            for (uint32_t begin = 0; begin < count; begin += min_range) {
                const uint32_t end = std::min(count, begin + min_range);
                job->pending.fetch_add(1);
                self->queue_.push_back(Range{job, begin, end});
            }
        }
        self->wake_.notify_all();
        return job;
    }

    static void finish(void* host_task, void* user) {
        auto* self = static_cast<HostJobSystem*>(user);
        auto* job = static_cast<Job*>(host_task);
        while (job->pending.load() > 0) {
            Range range;
            if (self->take(range)) {
                self->execute(range, 0);
            } else {
                std::this_thread::yield();
            }
        }
        delete job;
    }

    std::atomic<uint32_t> enqueued{0};

  private:
    struct Job {
        cloth_task_fn* task;
        void* context;
        std::atomic<uint32_t> pending;
    };
    struct Range {
        Job* job;
        uint32_t begin, end;
    };

    bool take(Range& range) {
        std::lock_guard<std::mutex> lock(mutex_);
        if (queue_.empty()) return false;
        range = queue_.front();
        queue_.pop_front();
        return true;
    }
    void execute(const Range& range, uint32_t worker) {
        range.job->task(range.begin, range.end, worker, range.job->context);
        range.job->pending.fetch_sub(1);
    }
    void run(uint32_t worker) {
        for (;;) {
            Range range;
            {
                std::unique_lock<std::mutex> lock(mutex_);
                wake_.wait(lock, [&] { return stop_ || !queue_.empty(); });
                if (stop_) return;
                range = queue_.front();
                queue_.pop_front();
            }
            execute(range, worker);
        }
    }

    std::mutex mutex_;
    std::condition_variable wake_;
    std::deque<Range> queue_;
    bool stop_ = false;
    std::vector<std::thread> threads_;
};

#ifdef CLOTH_SANITIZED_BUILD
constexpr int kSteps = 20;  // sanitizers slow the spinning pool 70x on two cores
const std::vector<uint32_t> kWorkerCounts = {2u, 3u};
#else
constexpr int kSteps = 300;
const std::vector<uint32_t> kWorkerCounts = {1u, 2u, 3u, 4u, 8u};
#endif

uint64_t fnv1a(uint64_t hash, const void* data, size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i) hash = (hash ^ bytes[i]) * 1099511628211ull;
    return hash;
}

// 300 steps of a 40 x 40 flag in wind (seven particle groups) with the
// default solver (multigrid-preconditioned PCG: its first coarse level is
// gathered by every worker, the cycle below runs on one thread between
// barriers) and at least two substeps per step, and a
// second flag in the same world so the stages of two cloths share the
// workers. Hash of every cloth's positions and velocities.
// spin_us: cloth_world_set_worker_spin (0: keep the default).
uint64_t flag_hash(const cloth_world_desc& world, uint32_t spin_us = 0, uint32_t flags = 2) {
    SceneConfig config;
    config.kind = SceneKind::kFlagInWind;
    config.resolution = 40;
    config.damping = 0.1f;
    config.solver.iterations = 2;
    config.solver.substeps = 2;
    config.world = world;
    config.copies = flags;
    Scene scene(config);
    EXPECT_TRUE(scene.ok()) << scene.error();
    if (spin_us > 0) {
        EXPECT_EQ(cloth_world_set_worker_spin(scene.world(), spin_us), CLOTH_OK);
    }
    for (int step = 0; step < kSteps; ++step) EXPECT_EQ(scene.step(1.0f / 60.0f), CLOTH_OK);
    uint64_t hash = 14695981039346656037ull;
    std::vector<float> values(3 * static_cast<size_t>(scene.particle_count()));
    for (cloth_id cloth : scene.cloths()) {
        EXPECT_EQ(cloth_read_positions(cloth, values.data(), static_cast<uint32_t>(values.size())), CLOTH_OK);
        hash = fnv1a(hash, values.data(), values.size() * sizeof(float));
        EXPECT_EQ(cloth_read_velocities(cloth, values.data(), static_cast<uint32_t>(values.size())),
                  CLOTH_OK);
        hash = fnv1a(hash, values.data(), values.size() * sizeof(float));
    }
    return hash;
}

TEST(Determinism, FlagHashIsTheSameForEveryWorkerCountAndForTheHostJobSystem) {
    cloth_world_desc serial = cloth_default_world_desc();
    const uint64_t reference = flag_hash(serial);
    for (uint32_t workers : kWorkerCounts) {
        cloth_world_desc desc = cloth_default_world_desc();
        desc.worker_count = workers;
        EXPECT_EQ(flag_hash(desc), reference) << workers << " workers";
    }
    // Workers that sleep after every stage (1 us of polling) or poll for a
    // whole second: the schedule changes, the bits do not.
    for (uint32_t spin_us : {1u, 1000000u}) {
        cloth_world_desc desc = cloth_default_world_desc();
        desc.worker_count = 2;
        EXPECT_EQ(flag_hash(desc, spin_us), reference) << "2 workers polling for " << spin_us << " us";
    }
    HostJobSystem host;
    EXPECT_EQ(flag_hash(host.world_desc()), reference) << "host job system";
    EXPECT_GT(host.enqueued.load(), static_cast<uint32_t>(kSteps))
        << "the host's job system ran the step's stages";
}

// Five flags: on fewer than five workers each worker runs whole flags
// (world_whole_cloths.cpp), on eight every stage of every flag runs as a
// round over the workers. The bits are the same either way.
TEST(Determinism, AFieldIsBitIdenticalWhetherWorkersRunWholeClothsOrRoundsOfStages) {
    const uint64_t reference = flag_hash(cloth_default_world_desc(), 0, 5);
    for (uint32_t workers : {2u, 4u, 8u}) {
        cloth_world_desc desc = cloth_default_world_desc();
        desc.worker_count = workers;
        EXPECT_EQ(flag_hash(desc, 0, 5), reference) << workers << " workers";
    }
    HostJobSystem host;
    EXPECT_EQ(flag_hash(host.world_desc(), 0, 5), reference) << "host job system";
}

TEST(Determinism, HostCallbacksAreValidated) {
    cloth_world_desc desc = cloth_default_world_desc();
    desc.enqueue_task = &HostJobSystem::enqueue;
    cloth_world_id world{};
    desc.worker_count = 2;
    EXPECT_EQ(cloth_world_create(&desc, &world), CLOTH_ERROR_INVALID_VALUE) << "enqueue without finish";
    desc.finish_task = &HostJobSystem::finish;
    desc.worker_count = 0;
    EXPECT_EQ(cloth_world_create(&desc, &world), CLOTH_ERROR_INVALID_COUNT) << "host workers unknown";
    desc = cloth_default_world_desc();
    desc.worker_count = 257;
    EXPECT_EQ(cloth_world_create(&desc, &world), CLOTH_ERROR_INVALID_COUNT) << "too many workers";
    EXPECT_EQ(world.index1, 0u) << "no world was created";
}

}  // namespace
