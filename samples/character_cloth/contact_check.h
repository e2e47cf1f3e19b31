// The garments-touch checks: the closest two particles of two garments,
// and of one garment beyond its rest neighbours, at the end of a frame,
// by brute force (a check, so the plainest correct way; about 1.5 M pairs
// at most here).
#pragma once

#include <vector>

namespace character_cloth {

// The least distance between a point of `a` and a point of `b` (xyz
// each), or `beyond` when none is closer than that.
float closest_between(const std::vector<float>& a, const std::vector<float>& b, float beyond);

// The least distance between two points of one garment (`x`, xyz) whose
// rest positions (`rest`) are at least `apart` from each other, or
// `beyond` when none is closer than that.
float closest_within(const std::vector<float>& x, const std::vector<float>& rest, float apart, float beyond);

}  // namespace character_cloth
