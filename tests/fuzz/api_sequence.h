// The fuzz harness of the C API: decodes arbitrary bytes into a sequence of
// C API calls over a small table of handles and checks the contract after
// each call. The libFuzzer target (fuzz_main.cpp) and the replay test
// (replay_main.cpp, plain g++ build) both run exactly this code.
//
// Written by hand: the byte format is this project's own (an opcode byte,
// then operands), so that libFuzzer's mutations map to whole API calls.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace cloth_fuzz {

// Opcodes: the first byte of each call, taken modulo kOpCount. New API
// areas append new opcodes (old corpus files keep their meaning).
enum Op : uint8_t {
    kWorldCreate,
    kWorldDestroy,
    kWorldSetGravity,
    kFabricGrid,
    kFabricMesh,
    kFabricObj,
    kFabricDestroy,
    kFabricQuery,
    kClothCreate,
    kClothDestroy,
    kStep,
    kParticleEdit,  // pin, unpin, set_positions, set_pin_targets
    kIsPinned,
    kSolver,    // set/get solver settings
    kMaterial,  // spring params, aero, wind
    kRead,      // positions, velocities, normals
    kStats,
    kAllocatorSchedule,  // make a world's allocator fail after n more allocations
    kNullArguments,      // a function called with a NULL pointer argument
    kSelfCollision,      // set/get self-collision, its stats
    kProfiling,          // profiling, frame profile, task records, trace JSON, zone callbacks
    kBody,               // create, destroy, set pose, teleport, velocity, get pose
    kCollider,           // create each shape, destroy, group bits
    kAttachment,         // attach, detach, get attachment, collision params, carrier, teleported
    kWorldShiftOrigin,   // origin rebasing
    kSnapshot,   // size, save (short capacity too), restore intact, damaged, cut, or into another cloth
    kCharacter,  // skin, joint matrices, skinned positions (set, read), max distances, backstops, body poses
    kClothContact,   // contact between two cloths: set (any pair, any values), get, count
    kLevelOfDetail,  // importance, the world's viewer, update rate: set (any values) and get
    kOpCount
};

struct RunStats {
    uint64_t calls = 0;     // C API calls made
    uint64_t rejected = 0;  // calls that returned an error code
    uint64_t steps = 0;     // cloth_step calls that advanced (CLOTH_OK or a restored cloth)
};

// Runs the sequence encoded in `data`. Aborts (after printing what broke)
// if the library breaks its contract: an unknown result code, an empty
// error message, a non-finite cloth after a step, a leak or a foreign or
// double free through the allocator callbacks, or a crash of its own.
RunStats run_api_sequence(const uint8_t* data, size_t size);

// Hand-written seed inputs (one per scenario), for the corpus.
std::vector<std::vector<uint8_t>> seed_inputs();

}  // namespace cloth_fuzz
