// Particle groups, the unit of parallel work, and staged algorithms, the
// shape every multi-pass algorithm of a step takes.
//
// A staged algorithm (the iterative solvers, the strain limiter,
// self-collision) is a sequence of rounds. A round is one pass over the
// particle groups, one task per group on any worker, with a barrier after
// it; serial bookkeeping after the barrier (a dot product's sum, an overlap
// test) picks the next round or ends the algorithm:
//
//   algorithm.begin(...);                              // serial
//   while (!algorithm.done()) {
//       algorithm.run(task) for every task             // parallel
//       algorithm.finish_round();                      // serial, after the barrier
//   }
//
// A frame runs these rounds beside the stages of other cloths
// (step/frame_plan.cpp). run_serially runs them alone on the calling thread,
// group by group, so an algorithm's serial form (tests, references) is its
// staged form and the two cannot drift apart.
#pragma once

#include <algorithm>
#include <cstdint>

namespace cloth {

// Particles per group: one padded chunk of the fabric's incidence lists
// (fabric.h) and one block of the solvers' fixed-order sums (solvers.h).
constexpr uint32_t kGroupSize = 256;

inline uint32_t group_count_of(uint32_t particle_count) {
    return (particle_count + kGroupSize - 1) / kGroupSize;
}

// One task of a round: particle group `group` of `group_count`, particles
// [begin, end).
struct GroupTask {
    uint32_t group = 0, group_count = 1;
    uint32_t begin = 0, end = 0;

    static GroupTask of(uint32_t group, uint32_t group_count, uint32_t particle_count) {
        return GroupTask{group, group_count, group * kGroupSize,
                         std::min(particle_count, (group + 1) * kGroupSize)};
    }
    // This group's share [first, last) of `items` items (springs, triangles,
    // regions) split evenly over the groups: each item has one owning group.
    void items(uint32_t count, uint32_t& first, uint32_t& last) const {
        first = static_cast<uint32_t>(static_cast<uint64_t>(count) * group / group_count);
        last = static_cast<uint32_t>(static_cast<uint64_t>(count) * (group + 1) / group_count);
    }
};

// The interface of a staged algorithm (see the top of this file).
class StagedAlgorithm {
  public:
    virtual bool done() const = 0;
    // The current round is one task over all particles, not one per group.
    virtual bool single_task() const { return false; }
    // The current round will be the last (known before it runs). A round
    // whose successor is decided after its barrier (a converging solve)
    // says false: such an algorithm is never the last stage of a frame.
    virtual bool last_round() const = 0;
    // One task of the current round (any worker; tasks of a round touch
    // disjoint outputs).
    virtual void run(const GroupTask& task) = 0;
    // After the round's barrier (serial): pick the next round, or finish.
    virtual void finish_round() = 0;

  protected:
    ~StagedAlgorithm() = default;
};

// Runs a staged algorithm, already begun, to its end on this thread:
// every round's tasks in group order, then its bookkeeping.
inline void run_serially(StagedAlgorithm& staged, uint32_t particle_count) {
    const uint32_t groups = group_count_of(particle_count);
    while (!staged.done()) {
        if (staged.single_task()) {
            staged.run(GroupTask{0, 1, 0, particle_count});
        } else {
            for (uint32_t g = 0; g < groups; ++g) staged.run(GroupTask::of(g, groups, particle_count));
        }
        staged.finish_round();
    }
}

}  // namespace cloth
