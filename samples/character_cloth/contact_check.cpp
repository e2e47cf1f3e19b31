#include "contact_check.h"

#include <algorithm>
#include <cmath>

namespace character_cloth {

float closest_between(const std::vector<float>& a, const std::vector<float>& b, float beyond) {
    // b's bounds grown by `beyond`: points of a outside them are farther.
    float low[3] = {INFINITY, INFINITY, INFINITY}, high[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t j = 0; j < b.size(); j += 3) {
        for (int d = 0; d < 3; ++d) {
            low[d] = std::min(low[d], b[j + d] - beyond);
            high[d] = std::max(high[d], b[j + d] + beyond);
        }
    }
    float least2 = beyond * beyond;
    for (size_t i = 0; i < a.size(); i += 3) {
        if (a[i] < low[0] || a[i] > high[0] || a[i + 1] < low[1] || a[i + 1] > high[1] || a[i + 2] < low[2] ||
            a[i + 2] > high[2])
            continue;
        for (size_t j = 0; j < b.size(); j += 3) {
            const float dx = a[i] - b[j], dy = a[i + 1] - b[j + 1], dz = a[i + 2] - b[j + 2];
            least2 = std::min(least2, dx * dx + dy * dy + dz * dz);
        }
    }
    return std::sqrt(least2);
}

float closest_within(const std::vector<float>& x, const std::vector<float>& rest, float apart, float beyond) {
    const auto squared = [](const std::vector<float>& p, size_t i, size_t j) {
        const float dx = p[i] - p[j], dy = p[i + 1] - p[j + 1], dz = p[i + 2] - p[j + 2];
        return dx * dx + dy * dy + dz * dz;
    };
    float least2 = beyond * beyond;
    for (size_t i = 0; i < x.size(); i += 3) {
        for (size_t j = i + 3; j < x.size(); j += 3) {
            const float now = squared(x, i, j);
            if (now < least2 && squared(rest, i, j) >= apart * apart) least2 = now;
        }
    }
    return std::sqrt(least2);
}

}  // namespace character_cloth
