#include "terrain.h"

#include <algorithm>
#include <cmath>

namespace vehicle_flag {
namespace {

// Gentle bumps everywhere (a few centimetres, metres apart) plus the kicker:
// a linear rise over ramp_length along +z, then a sheer drop.
float height_function(const TerrainLayout& layout, float x, float z) {
    float h = 0.06f * std::sin(0.9f * x + 0.3f) * std::sin(0.7f * z) + 0.04f * std::sin(0.23f * z + 0.5f * x);
    const float along = z - layout.ramp_start_z;
    if (along >= 0.0f && along <= layout.ramp_length) h += layout.ramp_height * along / layout.ramp_length;
    return h;
}

}  // namespace

Terrain::Terrain(const TerrainLayout& layout) : layout_(layout) {
    heights_.resize(static_cast<size_t>(layout_.columns) * layout_.rows);
    for (int j = 0; j < layout_.rows; ++j) {
        for (int i = 0; i < layout_.columns; ++i) {
            heights_[static_cast<size_t>(j) * layout_.columns + i] =
                height_function(layout_, layout_.min_x + i * layout_.cell, layout_.min_z + j * layout_.cell);
        }
    }
    const auto [lo, hi] = std::minmax_element(heights_.begin(), heights_.end());
    min_height_ = *lo;
    max_height_ = *hi;
}

// Bullet's default split of cell (i, j) (no flip, no diamond, no zigzag):
// triangles {(i, j), (i, j+1), (i+1, j)} and {(i+1, j), (i, j+1), (i+1, j+1)},
// i.e. along the diagonal from (i+1, j) to (i, j+1).
void Terrain::triangle_below(float x, float z, float corners[3][3]) const {
    const float u = std::clamp((x - layout_.min_x) / layout_.cell, 0.0f, layout_.columns - 1.0f);
    const float v = std::clamp((z - layout_.min_z) / layout_.cell, 0.0f, layout_.rows - 1.0f);
    const int i = std::min(static_cast<int>(u), layout_.columns - 2);
    const int j = std::min(static_cast<int>(v), layout_.rows - 2);
    const float fu = u - i, fv = v - j;
    int picks[3][2];
    if (fu + fv <= 1.0f) {
        const int lower[3][2] = {{i, j}, {i, j + 1}, {i + 1, j}};
        std::copy(&lower[0][0], &lower[0][0] + 6, &picks[0][0]);
    } else {
        const int upper[3][2] = {{i + 1, j}, {i, j + 1}, {i + 1, j + 1}};
        std::copy(&upper[0][0], &upper[0][0] + 6, &picks[0][0]);
    }
    for (int k = 0; k < 3; ++k) {
        corners[k][0] = layout_.min_x + picks[k][0] * layout_.cell;
        corners[k][1] = sample(picks[k][0], picks[k][1]);
        corners[k][2] = layout_.min_z + picks[k][1] * layout_.cell;
    }
}

float Terrain::height_at(float x, float z) const {
    float c[3][3];
    triangle_below(x, z, c);
    // Plane through the three corners, solved for y at (x, z).
    const float ax = c[1][0] - c[0][0], ay = c[1][1] - c[0][1], az = c[1][2] - c[0][2];
    const float bx = c[2][0] - c[0][0], by = c[2][1] - c[0][1], bz = c[2][2] - c[0][2];
    const float nx = ay * bz - az * by, ny = az * bx - ax * bz, nz = ax * by - ay * bx;
    const float cx = std::clamp(x, layout_.min_x, layout_.min_x + (layout_.columns - 1) * layout_.cell);
    const float cz = std::clamp(z, layout_.min_z, layout_.min_z + (layout_.rows - 1) * layout_.cell);
    return c[0][1] - (nx * (cx - c[0][0]) + nz * (cz - c[0][2])) / ny;
}

void Terrain::normal_at(float x, float z, float out_normal[3]) const {
    float c[3][3];
    triangle_below(x, z, c);
    const float ax = c[1][0] - c[0][0], ay = c[1][1] - c[0][1], az = c[1][2] - c[0][2];
    const float bx = c[2][0] - c[0][0], by = c[2][1] - c[0][1], bz = c[2][2] - c[0][2];
    float n[3] = {ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx};
    const float scale = (n[1] < 0.0f ? -1.0f : 1.0f) / std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; ++k) out_normal[k] = n[k] * scale;
}

void Terrain::patch_mesh(float cx, float cz, float half, std::vector<float>* positions,
                         std::vector<uint32_t>* indices) const {
    positions->clear();
    indices->clear();
    const auto index_range = [&](float center, float origin, int count, int* lo, int* hi) {
        *lo = std::clamp(static_cast<int>(std::floor((center - half - origin) / layout_.cell)), 0, count - 1);
        *hi = std::clamp(static_cast<int>(std::ceil((center + half - origin) / layout_.cell)), 0, count - 1);
    };
    int i0, i1, j0, j1;
    index_range(cx, layout_.min_x, layout_.columns, &i0, &i1);
    index_range(cz, layout_.min_z, layout_.rows, &j0, &j1);
    if (i1 <= i0 || j1 <= j0) return;
    const uint32_t width = static_cast<uint32_t>(i1 - i0 + 1);
    for (int j = j0; j <= j1; ++j) {
        for (int i = i0; i <= i1; ++i) {
            positions->insert(positions->end(), {layout_.min_x + i * layout_.cell, sample(i, j),
                                                 layout_.min_z + j * layout_.cell});
        }
    }
    for (uint32_t j = 0; j + 1 < static_cast<uint32_t>(j1 - j0 + 1); ++j) {
        for (uint32_t i = 0; i + 1 < width; ++i) {
            const uint32_t a = j * width + i;
            indices->insert(indices->end(), {a, a + width, a + 1, a + 1, a + width, a + width + 1});
        }
    }
}

}  // namespace vehicle_flag
