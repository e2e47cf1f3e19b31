// A hash of raw bytes (64-bit FNV-1a) for "the same bits for every worker
// count" tests: equal hashes of the read-back floats, bit for bit.
#pragma once

#include <cstddef>
#include <cstdint>

namespace cloth_test {

constexpr uint64_t kBitsHashStart = 14695981039346656037ull;

inline uint64_t hash_bits(uint64_t hash, const void* data, size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i) hash = (hash ^ bytes[i]) * 1099511628211ull;
    return hash;
}

}  // namespace cloth_test
