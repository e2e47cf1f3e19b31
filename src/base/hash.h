// 64-bit hashes of byte ranges: XXH3 from Debian's libxxhash-dev, compiled
// into the including file (XXH_INLINE_ALL), so the library links nothing
// for it. Used for snapshot checksums and fabric identities.
#pragma once

#include <cstddef>
#include <cstdint>

#define XXH_INLINE_ALL
#include <xxhash.h>

namespace cloth {

// The hash of `size` bytes at `data`, continuing the hash `seed` (chain
// several ranges by passing each result as the next seed).
inline uint64_t hash_bytes(const void* data, size_t size, uint64_t seed = 0) {
    return XXH3_64bits_withSeed(data, size, seed);
}

}  // namespace cloth
