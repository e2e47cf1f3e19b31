// The "nothing changed" contract of the C API, written once: a rejected
// call returns its code, leaves a message in cloth_get_last_error() (and
// the same code and message in the world's log), and changes nothing a
// host can observe: the cloths' and bodies' state bit for bit, the memory
// the world holds, the caller's output arguments. The contract tests check
// it through contract_gtest.h, the fuzzer directly (this header and
// contract.cpp use no test framework).
#pragma once

#include <cloth/cloth.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "support/counting_allocator.h"

namespace cloth_test {

// Everything a host can read back about one cloth.
struct ClothState {
    uint32_t count = 0;
    std::vector<float> positions, velocities, normals;
    std::vector<float> masses;  // one per particle
    std::vector<uint8_t> pinned;
    std::vector<cloth_body_id> attached_to;  // per particle; null if not attached
    std::vector<float> attach_offsets;       // 3 per particle
    cloth_solver_settings solver{};
    cloth_strain_limit strain_limit{};
    cloth_stats stats{};
    cloth_collision_params collision{};
    cloth_self_collision_desc self_collision{};
    uint8_t teleported = 0;
    uint8_t sleeping = 0;
    float importance = 0;
    uint32_t update_rate = 0, update_phase = 0;
    // Pin targets, air and wind have no getter: the snapshot holds them.
    std::vector<unsigned char> snapshot;
};

struct BodyState {
    float position[3] = {};
    float rotation[4] = {};
};

// Reads the state; returns "" or which read failed.
std::string read_cloth_state(cloth_id cloth, ClothState* out);
std::string read_body_state(cloth_body_id body, BodyState* out);

struct Compare {
    // A cloth_step updates last_step_result and the solver diagnostics of a
    // cloth it restores after a failure: off when comparing across one.
    bool step_diagnostics = true;
    // Twin worlds hold the same bodies under other world indices: off when
    // comparing a cloth with its twin.
    bool world_of_body_ids = true;
};

// The first difference, bit for bit (NaN equals NaN of the same bits); "" if none.
std::string first_difference(const ClothState& before, const ClothState& after, Compare compare = {});
std::string first_difference(const BodyState& before, const BodyState& after);

// What a call must leave alone.
struct Watch {
    cloth_world_id world{};  // stepped by twin_divergence
    std::vector<cloth_id> cloths;
    std::vector<cloth_body_id> bodies;
    const CountingAllocator* memory = nullptr;  // the world's allocator: live bytes and blocks
    struct Bytes {
        const void* data;
        size_t size;
        const char* what;
    };
    std::vector<Bytes> outputs;  // output arguments
};

// Captures everything a Watch names when constructed; what_changed() reads
// it again and says what differs ("" if nothing).
class Unchanged {
  public:
    explicit Unchanged(const Watch& watch, Compare compare = {});
    std::string what_changed() const;

  private:
    struct Captured {
        std::vector<ClothState> cloths;
        std::vector<BodyState> bodies;
        size_t live_bytes = 0;
        size_t live_blocks = 0;
        std::vector<std::vector<unsigned char>> outputs;
        std::string read_error;
    };
    Captured capture() const;

    const Watch& watch_;
    Compare compare_;
    Captured before_;
};

// The checks of every call's report: a known code with a name, and on
// failure a non-NULL, non-empty cloth_get_last_error(). "" if it holds.
std::string report_problem(cloth_result result);

// A call made on a thread of its own, so that cloth_get_last_error() before
// it is "" and after it is this call's message.
struct CallOutcome {
    cloth_result result = CLOTH_OK;
    bool error_before_null = false;
    bool error_after_null = false;
    std::string error_before;
    std::string error_after;
};
CallOutcome call_on_fresh_thread(const std::function<cloth_result()>& call);

enum class Logged {
    kYes,    // the world's log received exactly one error, with the call's code and message
    kMaybe,  // no error logged, or one as above
    kNo,     // a call that names no live world: no log hears of it (cloth.h, "Which log hears of an error")
};

// Each clause of the rejection contract `outcome` broke (empty if none):
// the expected code, the last error before ("") and after (set), and the
// world's log (`errors`: the error entries it received during the call).
std::vector<std::string> rejection_problems(cloth_result expected, const CallOutcome& outcome,
                                            const std::vector<LogEntry>& errors, Logged logged);

// Steps two worlds built by the same calls `frames` times together (after
// `before_each(frame)`, if given) and compares their cloths and bodies
// pairwise: "" if they stay bit-identical, else the first difference. A
// failed call that changed hidden state (gravity, wind, spring parameters,
// pin targets, a collider half made) shows here.
std::string twin_divergence(const Watch& a, const Watch& b, int frames,
                            const std::function<void(int frame)>& before_each = {});

std::string result_name(cloth_result result);  // "CLOTH_ERROR_X (n)"

// "" or where two arrays of 3 floats per particle differ, bit for bit.
std::string float_difference(const char* what, const std::vector<float>& before,
                             const std::vector<float>& after);

// Reads a one-byte flag whatever the function's flag type (bool today,
// uint8_t as well): read_flag(cloth_is_pinned, cloth, i, &byte).
template <typename Flag>
cloth_result read_flag(cloth_result (*get)(cloth_id, uint32_t, Flag*), cloth_id cloth, uint32_t index,
                       uint8_t* out) {
    Flag flag{};
    const cloth_result r = get(cloth, index, &flag);
    *out = flag ? 1 : 0;
    return r;
}
template <typename Flag>
cloth_result read_flag(cloth_result (*get)(cloth_id, Flag*), cloth_id cloth, uint8_t* out) {
    Flag flag{};
    const cloth_result r = get(cloth, &flag);
    *out = flag ? 1 : 0;
    return r;
}

// An output flag argument that is one byte of the caller's, whatever the
// function's flag type: a test fills the byte with a pattern and sees
// whether a rejected call wrote it.
struct FlagOut {
    unsigned char* byte;
    template <typename T>
    operator T*() const {
        static_assert(sizeof(T) == 1, "a flag is one byte");
        return reinterpret_cast<T*>(byte);
    }
};

}  // namespace cloth_test
