// Hand-written seed inputs of the fuzz harness: one short scenario per
// area of the C API, encoded in the harness's byte format (api_sequence.cpp
// decodes it; the two must change together). `cloth_fuzz_replay
// --write-seeds DIR` writes them to the corpus.
#include <cstdint>
#include <vector>

#include "api_sequence.h"

namespace cloth_fuzz {
namespace {

// Byte writer mirroring Harness's decoder.
struct Encoder {
    std::vector<uint8_t> bytes;

    Encoder& u8(uint8_t v) {
        bytes.push_back(v);
        return *this;
    }
    Encoder& u16(uint16_t v) { return u8(v & 0xFF).u8(v >> 8); }
    Encoder& u32(uint32_t v) { return u16(v & 0xFFFF).u16(v >> 16); }
    Encoder& op(Op o) { return u8(o); }
    // Edge values, by their index in Bytes::any_float's table.
    Encoder& edge(uint8_t index) { return u8(index); }
    // A small value v in -8..8 with a step of 1/16.
    Encoder& small(float v) { return u8(100).u8(static_cast<uint8_t>(v * 16.0f + 128.0f)); }
    Encoder& slot(uint8_t s) { return u8(s); }

    // A world; `jobs`: worker_count in bits 0-1, bit 2 the host job system.
    Encoder& world(uint8_t flags, uint8_t jobs = 0) { return op(kWorldCreate).u8(flags).u8(jobs); }
    Encoder& grid(uint8_t world, uint8_t columns, uint8_t rows) {
        return op(kFabricGrid).slot(world).u8(0).u8(columns).u8(rows);
    }
    Encoder& cloth(uint8_t world, uint8_t fabric) { return op(kClothCreate).slot(world).slot(fabric).u8(0); }
    Encoder& step(uint8_t world, int times) {
        for (int i = 0; i < times; ++i) op(kStep).slot(world).u8(0);
        return *this;
    }
    // Pin (what = 0) two particles.
    Encoder& pin2(uint8_t cloth, uint8_t a, uint8_t b) {
        op(kParticleEdit).slot(cloth).u8(0).u8(2).u8(a).u8(b);
        for (int k = 0; k < 6; ++k) small(0.0f);
        return *this;
    }
    Encoder& wind(uint8_t cloth, float x, float z) {
        return op(kMaterial).slot(cloth).u8(2).small(x).small(0.0f).small(z);
    }
    Encoder& read(uint8_t cloth, uint8_t what) { return op(kRead).slot(cloth).u8(what).u8(0); }
};

}  // namespace

std::vector<std::vector<uint8_t>> seed_inputs() {
    std::vector<std::vector<uint8_t>> seeds;

    // A pinned flag in wind on the default heap and two worker threads,
    // stepped and read back.
    Encoder flag;
    flag.world(0, 2).grid(0, 16, 12).cloth(0, 0).pin2(0, 0, 15).wind(0, 6.0f, 1.0f).step(0, 12);
    flag.read(0, 0).read(0, 1).read(0, 2).op(kStats).slot(0).u8(0);
    seeds.push_back(flag.bytes);

    // A mesh strip (14 vertices, 12 triangles) on the counting allocator,
    // its fabric released while the cloth lives, then the cloth destroyed.
    Encoder mesh;
    mesh.world(1).op(kFabricMesh).slot(0).u8(0).u8(14).u8(12);
    mesh.cloth(0, 0).step(0, 4).op(kFabricDestroy).slot(0).step(0, 2).op(kClothDestroy).slot(0).step(0, 1);
    seeds.push_back(mesh.bytes);

    // A mesh with an index out of range and a NaN vertex (flags: 1 float
    // edit, 1 index edit).
    Encoder bad_mesh;
    bad_mesh.world(1).op(kFabricMesh).slot(0).u8(1 | (1 << 3)).u8(14).u8(12);
    bad_mesh.u16(5).edge(13).u16(7).u8(0).u8(15);  // NaN, then index 15 of 14 vertices
    seeds.push_back(bad_mesh.bytes);

    // An OBJ quad (two triangles) made into a cloth.
    Encoder obj;
    obj.world(0).op(kFabricObj).slot(0).u8(2).u8(0).cloth(0, 0).step(0, 3);
    seeds.push_back(obj.bytes);

    // Allocation failures: the counting allocator fails after 3 more
    // allocations during cloth and fabric creation, then recovers.
    Encoder oom;
    oom.world(1).grid(0, 8, 8).op(kAllocatorSchedule).u8(0).u8(3).cloth(0, 0).grid(0, 8, 8);
    oom.op(kAllocatorSchedule).u8(0).u8(255).cloth(0, 0).step(0, 2);
    seeds.push_back(oom.bytes);

    // Huge stiffness with the explicit integrator goes non-finite; the
    // step restores the cloth and a second cloth keeps advancing.
    Encoder blow_up;
    blow_up.world(0).grid(0, 8, 8).cloth(0, 0);
    blow_up.op(kClothCreate).slot(0).slot(0).u8(4 | 8);
    blow_up.edge(7).small(0.0f).edge(7).small(0.0f).edge(7).small(0.0f);  // 1e30 N/m springs
    blow_up.u8(3).u8(1).u8(1).small(0.5f).u8(50).u8(1);                   // explicit, 1 substep
    blow_up.step(0, 3);
    seeds.push_back(blow_up.bytes);

    // The CG reference solver on a small grid, on the host job system.
    Encoder cg;
    cg.world(0, 4 | 1).grid(0, 6, 6).cloth(0, 0);
    cg.op(kSolver).slot(0).u8(2).u8(2).u8(1).u8(1).small(0.0625f).u8(40);
    cg.step(0, 2);
    seeds.push_back(cg.bytes);

    // Stale and garbage handles, NULL arguments, destroy in a bad order.
    Encoder stale;
    stale.world(4).grid(0, 4, 4).cloth(0, 0).op(kWorldDestroy).slot(0);
    stale.step(0, 1).op(kClothDestroy).slot(0).op(kFabricDestroy).slot(0);
    for (uint8_t k = 0; k < 12; ++k) stale.op(kNullArguments).slot(0).slot(0).slot(0).u8(k);
    stale.op(kClothDestroy).u8(250).u8(1).u16(1).u16(1).u16(1);
    seeds.push_back(stale.bytes);

    // Self-collision on a flag, stepped, then its stats read and turned off.
    Encoder self;
    self.world(0).grid(0, 12, 12).cloth(0, 0).pin2(0, 0, 11);
    self.op(kSelfCollision).slot(0).u8(0).u8(1).step(0, 4);
    self.op(kSelfCollision).slot(0).u8(2).u8(0).op(kSelfCollision).slot(0).u8(1);
    self.op(kSelfCollision).slot(0).u8(0).u8(0).step(0, 1);
    seeds.push_back(self.bytes);

    // Profiling on a world with two workers: records, profile, trace JSON, zones.
    Encoder profile;
    profile.world(0, 2).grid(0, 8, 8).cloth(0, 0);
    // zones on (what % 6 == 5 with bit 0x40)
    profile.op(kProfiling).slot(0).u8(0).u8(32).op(kProfiling).slot(0).u8(0x41).u32(3).step(0, 2);
    profile.op(kProfiling).slot(0).u8(1).u8(0).op(kProfiling).slot(0).u8(2).u8(40);
    profile.op(kProfiling).slot(0).u8(3).u8(0).op(kProfiling).slot(0).u8(3).u8(255);
    profile.op(kProfiling).slot(0).u8(0).u8(0);
    seeds.push_back(profile.bytes);

    // A frame budget no step meets (every step returns CLOTH_ERROR_OVER_BUDGET)
    // with a quality policy on the cloth, then lifted.
    Encoder budget;
    budget.world(0).grid(0, 8, 8).cloth(0, 0);
    budget.op(kProfiling).slot(0).u8(0x40).u8(140).slot(0).step(0, 3);
    budget.op(kProfiling).slot(0).u8(4).u8(0).slot(0).step(0, 1);
    seeds.push_back(budget.bytes);

    // Contact: a body carrying a flag (three particles attached where they
    // are), a sphere on the body, a ground plane and a height field; the body
    // moves, the cloth gets a carrier with teleport-and-reset, the body
    // teleports; then detach, destroy the body and a collider, step on.
    Encoder contact;
    contact.world(0).grid(0, 8, 8).cloth(0, 0);
    contact.op(kBody).u8(0).small(0.0f).small(1.0f).small(0.0f).u8(0).slot(0);  // create body 0
    contact.op(kAttachment).slot(0).u8(0x42).u8(3).u8(0).u8(1).u8(2);           // attach 0, 1, 2 ...
    for (int k = 0; k < 6; ++k) contact.small(0.0f);
    contact.slot(0);                                                    // ... to body 0, where they are
    contact.op(kCollider).u8(0x12).slot(0).slot(0).u8(0).u8(0).u8(16);  // sphere on body 0
    for (int k = 0; k < 3; ++k) contact.u8(0).u8(10);
    contact.op(kCollider).u8(3).slot(0).u8(0);  // plane y <= -1
    contact.u8(200).edge(3).u8(200).edge(0).u8(0).u8(60).u8(200).edge(0);
    contact.op(kCollider).u8(6).slot(0).u8(0).u8(0).u8(32).u8(0).u8(32).u8(0).u8(0).u8(0).u8(
        0);  // height field
    contact.u8(4).u8(4);
    for (int k = 0; k < 16; ++k) contact.u8(0).u8(static_cast<uint8_t>(k * 3));
    contact.u8(0);
    contact.op(kAttachment).slot(0).u8(3).u8(1).small(0.0625f);  // collision thickness
    contact.op(kAttachment).slot(0).u8(4).u8(16 | 64).small(1.0f).u32(1).u8(2).slot(0);  // carrier, reset
    contact.step(0, 2);
    contact.op(kBody).u8(2).small(0.5f).small(1.0f).small(0.0f).u8(0).slot(0).step(0, 2);  // move
    contact.op(kBody).u8(3).small(6.0f).small(1.0f).small(0.0f).u8(0).slot(0).step(0, 1);  // teleport
    contact.op(kAttachment).slot(0).u8(5).op(kAttachment).slot(0).u8(2).u8(1);  // teleported? attached?
    contact.op(kAttachment).slot(0).u8(1).u8(2).u8(0).u8(1).step(0, 1);         // detach 0, 1
    contact.op(kBody).u8(1).small(0.0f).small(0.0f).small(0.0f).u8(0).slot(0).step(0, 1);  // destroy body
    contact.op(kCollider).u8(7).slot(1).step(0, 1);                                        // destroy plane
    seeds.push_back(contact.bytes);

    // Snapshots: restored intact, with two bytes changed, cut short,
    // lengthened, with a NaN written over a value, into a second cloth of
    // the same fabric, and saved into a buffer one byte short; stepped on.
    Encoder snapshot;
    snapshot.world(0).grid(0, 8, 8).cloth(0, 0).cloth(0, 0).step(0, 2);
    snapshot.op(kSnapshot).slot(0).u8(0).u8(0);                                       // intact
    snapshot.op(kSnapshot).slot(0).u8(0).u8(1).u8(1).u16(7).u8(0x10).u16(300).u8(1);  // two bytes changed
    snapshot.op(kSnapshot).slot(0).u8(0).u8(2).u16(50);                               // cut to 50 bytes
    snapshot.op(kSnapshot).slot(0).u8(0).u8(3).u8(0);                                 // one byte more
    snapshot.op(kSnapshot).slot(0).u8(0).u8(4).edge(13).u16(40);                      // NaN over float 40
    snapshot.op(kSnapshot).slot(0).u8(2).u8(0).slot(1);                               // into cloth 1
    snapshot.op(kSnapshot).slot(0).u8(1);                                             // capacity one short
    snapshot.step(0, 2);
    seeds.push_back(snapshot.bytes);

    // Character cloth: an 8x8 cloth skinned to two joints (the top row to
    // joint 0), max distances (0 on every fifth particle: pins) and
    // backstops, identity joint matrices, stepped, the skin read back.
    Encoder character;
    character.world(0, 2).grid(0, 8, 8).cloth(0, 0);
    character.op(kCharacter).slot(0).u8(0).u8(1).u8(0);  // skin: 2 joints, 1 influence
    for (int v = 0; v < 64; ++v) character.u8(v < 8 ? 0 : 1);
    character.op(kCharacter).slot(0).u8(3);                         // max distances
    character.op(kCharacter).slot(0).u8(4);                         // backstops
    character.op(kCharacter).slot(0).u8(1).u8(2).u8(0).step(0, 4);  // two 4x4 matrices, stepped
    character.op(kCharacter).slot(0).u8(5).step(0, 2);              // read the skin
    seeds.push_back(character.bytes);

    // Contact between two 8x8 cloths of one fabric, one on the other (every
    // particle coincident), turned on, stepped, read back and counted.
    Encoder pair;
    pair.world(0, 2).grid(0, 8, 8).cloth(0, 0).cloth(0, 0);
    pair.op(kClothContact).slot(0).slot(1).u8(0).u8(1).u8(2);  // on, thickness 0.03 m
    pair.step(0, 3);
    pair.op(kClothContact).slot(1).slot(0).u8(1);  // read back
    pair.op(kClothContact).slot(0).slot(1).u8(2);  // count
    seeds.push_back(pair.bytes);

    // Three cloths at rates 2, 4 and 8 (the last with importance 0.5 and a
    // viewer), stepped between reads of their rates.
    Encoder rates;
    rates.world(0, 2).grid(0, 8, 8).cloth(0, 0).cloth(0, 0).cloth(0, 0);
    rates.op(kLevelOfDetail).u8(3).slot(0).u8(1);            // rate 2
    rates.op(kLevelOfDetail).u8(3).slot(1).u8(2);            // rate 4
    rates.op(kLevelOfDetail).u8(3).slot(2).u8(3);            // rate 8
    rates.op(kLevelOfDetail).u8(0).slot(2).u8(2);            // importance 0.5
    rates.op(kLevelOfDetail).u8(2).u8(0).u8(0).u8(0).u8(0);  // a viewer
    rates.step(0, 5);
    rates.op(kLevelOfDetail).u8(4).slot(1);        // read the rate and phase
    rates.op(kLevelOfDetail).u8(3).slot(2).u8(0);  // back to rate 1
    rates.step(0, 9);
    seeds.push_back(rates.bytes);

    return seeds;
}

}  // namespace cloth_fuzz
