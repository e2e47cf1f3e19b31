// The garments-touch check: the closest two particles of two garments at
// the end of a frame, by brute force over the pairs whose bounds meet
// (a check, so the plainest correct way; about 1.5 M pairs at most here).
#pragma once

#include <vector>

namespace character_cloth {

// The least distance between a point of `a` and a point of `b` (xyz
// each), or `beyond` when none is closer than that.
float closest_between(const std::vector<float>& a, const std::vector<float>& b, float beyond);

}  // namespace character_cloth
