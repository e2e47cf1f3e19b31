// The host engine's job system behind the task seam (task_system.h):
// cloth_world_desc.enqueue_task / finish_task, Box2D v3.1 style. The host
// runs our range task on its own workers, or inline (enqueue returns NULL).
#pragma once

#include <cloth/cloth.h>

#include "jobs/task_system.h"

namespace cloth {

class HostTasks final : public TaskSystem {
  public:
    HostTasks(cloth_enqueue_task_fn* enqueue, cloth_finish_task_fn* finish, void* user, uint32_t workers)
        : enqueue_(enqueue), finish_(finish), user_(user), workers_(workers > 0 ? workers : 1) {}

    uint32_t worker_count() const override { return workers_; }
    void parallel_for(uint32_t count, uint32_t min_range, RangeTask task, void* context) override {
        if (count == 0) return;
        void* host_task = enqueue_(task, count, min_range > 0 ? min_range : 1, context, user_);
        if (host_task) finish_(host_task, user_);
    }

  private:
    cloth_enqueue_task_fn* enqueue_;
    cloth_finish_task_fn* finish_;
    void* user_;
    uint32_t workers_;
};

}  // namespace cloth
