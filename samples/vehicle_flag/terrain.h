// The sample's ground: a height grid with gentle bumps and a kicker ramp for
// the jump, seen by Bullet as a btHeightfieldTerrainShape (built in
// vehicle_world.cpp) and by the sample itself for the terrain checks and the
// picture. Heights are exact on the grid and piecewise planar in between, on
// the same two triangles per cell that Bullet uses.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace vehicle_flag {

struct TerrainLayout {
    float min_x = -32.0f, min_z = -20.0f;  // world position of sample (0, 0)
    float cell = 0.5f;                     // m between samples, both directions
    int columns = 129;                     // samples along x
    int rows = 1001;                       // samples along z
    float ramp_start_z = 330.0f;           // the kicker rises from here...
    float ramp_length = 9.0f;              // ...over this distance along +z...
    float ramp_height = 1.3f;              // ...to this height, then drops back
};

class Terrain {
  public:
    explicit Terrain(const TerrainLayout& layout = {});

    const TerrainLayout& layout() const { return layout_; }
    // Samples, x fastest: height of sample (i, j) at world (min_x + i cell, min_z + j cell).
    const std::vector<float>& heights() const { return heights_; }
    float min_height() const { return min_height_; }
    float max_height() const { return max_height_; }

    // Height of the triangulated surface below (x, z); clamps outside the grid.
    float height_at(float x, float z) const;
    // Upward unit normal of the triangle below (x, z).
    void normal_at(float x, float z, float out_normal[3]) const;

    // A render mesh of the square [cx - half, cx + half] x [cz - half, cz + half]
    // (clipped to the grid): xyz positions and triangle indices.
    void patch_mesh(float cx, float cz, float half, std::vector<float>* positions,
                    std::vector<uint32_t>* indices) const;

  private:
    float sample(int i, int j) const { return heights_[static_cast<size_t>(j) * layout_.columns + i]; }
    // Cell coordinates and the three corners of the triangle below (x, z).
    void triangle_below(float x, float z, float corners[3][3]) const;

    TerrainLayout layout_;
    std::vector<float> heights_;
    float min_height_ = 0.0f, max_height_ = 0.0f;
};

}  // namespace vehicle_flag
