// The loop that runs begun frames to their end, written once for World::step
// (every awake cloth of a world) and ClothInstance::step (one cloth alone).
// Each round runs the current stage of every cloth whose frame is not done
// (run_round: all their tasks, in parallel, returning after the barrier),
// then each cloth's serial bookkeeping picks its next stage. Cloths with
// fewer stages finish early and drop out of later rounds.
#pragma once

#include <cstdint>

#include "step/cloth_instance.h"

namespace cloth {

// `cloths`: `count` cloths on which begin_frame was called.
template <class RunRound>
void run_frames(ClothInstance* const* cloths, uint32_t count, RunRound&& run_round) {
    for (;;) {
        bool any = false;
        for (uint32_t c = 0; c < count; ++c) {
            if (cloths[c]->frame_done()) continue;
            cloths[c]->prepare_stage();
            any = true;
        }
        if (!any) return;
        run_round();
        for (uint32_t c = 0; c < count; ++c) {
            if (!cloths[c]->frame_done()) cloths[c]->finish_stage();
        }
    }
}

}  // namespace cloth
