// A snapshot is restored exactly as saved or refused, and a refusal changes nothing.
#include <cstdint>
#include <string>
#include <vector>

#include "bad_input/fixture.h"

namespace cloth_bad_input {
namespace {

std::vector<unsigned char> Snapshot(cloth_id cloth) {
    size_t size = 0;
    EXPECT_EQ(cloth_get_snapshot_size(cloth, &size), CLOTH_OK);
    std::vector<unsigned char> bytes(size);
    EXPECT_EQ(cloth_save_snapshot(cloth, bytes.data(), bytes.size()), CLOTH_OK);
    return bytes;
}

// Every byte of a snapshot changed in turn, every bit of its first 128
// bytes (the header and more) flipped in turn, and the snapshot cut short
// or lengthened: each is refused as corrupt, and the cloth stays bit for
// bit what it was (the watch compares its whole state, snapshot included).
TEST_F(BadInput, RestoringASnapshotWithAnyByteChangedIsRefusedAsCorruptAndChangesNothing) {
    // Move the cloth on from the state the snapshot holds, so that a
    // wrongly accepted snapshot shows as a change.
    std::vector<unsigned char> bytes = Snapshot(a_.cloth);
    for (const Scene* s : {&a_, &b_}) ASSERT_EQ(cloth_step(s->world, kFrame), CLOTH_OK);

    for (size_t i = 0; i < bytes.size(); ++i) {
        bytes[i] ^= 0xFF;
        ExpectRejected(CLOTH_ERROR_CORRUPT_SNAPSHOT, "byte " + std::to_string(i) + " inverted",
                       [&] { return cloth_restore_snapshot(a_.cloth, bytes.data(), bytes.size()); });
        bytes[i] ^= 0xFF;
        if (HasFailure()) return;  // one report, not thousands
    }
    for (size_t bit = 0; bit < 8 * std::min<size_t>(bytes.size(), 128); ++bit) {
        bytes[bit / 8] ^= static_cast<unsigned char>(1u << (bit % 8));
        ExpectRejected(CLOTH_ERROR_CORRUPT_SNAPSHOT, "bit " + std::to_string(bit) + " flipped",
                       [&] { return cloth_restore_snapshot(a_.cloth, bytes.data(), bytes.size()); });
        bytes[bit / 8] ^= static_cast<unsigned char>(1u << (bit % 8));
        if (HasFailure()) return;
    }
    for (size_t size : {size_t{0}, size_t{1}, size_t{16}, bytes.size() / 2, bytes.size() - 1}) {
        ExpectRejected(CLOTH_ERROR_CORRUPT_SNAPSHOT, "cut to " + std::to_string(size) + " bytes",
                       [&] { return cloth_restore_snapshot(a_.cloth, bytes.data(), size); });
    }
    std::vector<unsigned char> longer = bytes;
    longer.push_back(0);
    EXPECT_REJECTED(CLOTH_ERROR_CORRUPT_SNAPSHOT,
                    cloth_restore_snapshot(a_.cloth, longer.data(), longer.size()));
    const std::vector<unsigned char> zeros(bytes.size(), 0);
    EXPECT_REJECTED(CLOTH_ERROR_CORRUPT_SNAPSHOT,
                    cloth_restore_snapshot(a_.cloth, zeros.data(), zeros.size()));

    // The untouched snapshot still restores, into both worlds alike.
    for (const Scene* s : {&a_, &b_})
        EXPECT_EQ(cloth_restore_snapshot(s->cloth, bytes.data(), bytes.size()), CLOTH_OK)
            << cloth_get_last_error();
    EXPECT_EQ(Snapshot(a_.cloth), bytes) << "a restored snapshot saves as other bytes";
}

// A fabric's identity is its content: a snapshot restores into a cloth of
// a fabric built from the same description in another world, and is
// refused by a cloth of another fabric with as many particles.
TEST_F(BadInput, ASnapshotRestoresIntoAClothOfTheSameFabricAnywhereAndNoOther) {
    const std::vector<unsigned char> twin = Snapshot(b_.cloth);
    EXPECT_EQ(cloth_restore_snapshot(a_.cloth, twin.data(), twin.size()), CLOTH_OK) << cloth_get_last_error();

    CountingAllocator host;
    const cloth_world_desc wd = host.world_desc();
    cloth_world_id world{};
    ASSERT_EQ(cloth_world_create(&wd, &world), CLOTH_OK);
    cloth_grid_desc wider = SmallGrid();
    wider.u[0] = 1.5f;  // as many particles, other rest lengths
    cloth_fabric_id fabric{};
    ASSERT_EQ(cloth_fabric_create_grid(world, &wider, &fabric), CLOTH_OK);
    cloth_desc desc = cloth_default_desc();
    desc.fabric = fabric;
    cloth_id other_fabric_cloth{};
    ASSERT_EQ(cloth_create(world, &desc, &other_fabric_cloth), CLOTH_OK);
    const std::vector<unsigned char> foreign = Snapshot(other_fabric_cloth);
    ASSERT_EQ(foreign.size(), twin.size());
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_VALUE,
                    cloth_restore_snapshot(a_.cloth, foreign.data(), foreign.size()));

    cloth_grid_desc smaller = SmallGrid();
    smaller.columns = kColumns - 1;
    ASSERT_EQ(cloth_fabric_create_grid(world, &smaller, &fabric), CLOTH_OK);
    desc.fabric = fabric;
    cloth_id fewer{};
    ASSERT_EQ(cloth_create(world, &desc, &fewer), CLOTH_OK);
    const std::vector<unsigned char> small = Snapshot(fewer);
    EXPECT_REJECTED(CLOTH_ERROR_INVALID_COUNT, cloth_restore_snapshot(a_.cloth, small.data(), small.size()));
    ASSERT_EQ(cloth_world_destroy(world), CLOTH_OK);
}

}  // namespace
}  // namespace cloth_bad_input
