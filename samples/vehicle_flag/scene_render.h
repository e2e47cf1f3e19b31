// Pictures of the course: a few moments of the flag on the vehicle, each
// seen by a chase camera, tiled into one PNG with the shared software
// rasterizer (samples/common/render_png.h).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "terrain.h"
#include "vehicle_world.h"

namespace vehicle_flag {

// Everything needed to draw one moment after the fact.
struct Moment {
    std::string label;
    float time = 0.0f;
    btTransform chassis;
    std::vector<btTransform> wheels;
    std::vector<float> flag_positions, flag_normals;
};

Moment capture_moment(const std::string& label, float time, const VehicleWorld& vehicle,
                      const std::vector<float>& flag_positions, const std::vector<float>& flag_normals);

// Renders one moment, seen by the chase camera, into width x height RGB
// pixels (rows top to bottom). Returns false with a message in *error on failure.
bool render_moment(const Moment& moment, const Terrain& terrain, const VehicleLayout& vehicle,
                   const std::vector<uint32_t>& flag_triangles, int width, int height,
                   std::vector<uint8_t>* rgb, std::string* error);

// Renders the moments as panels of panel_width x panel_height, two per row,
// into one PNG. Returns false with a message in *error on failure.
bool render_moments(const std::string& path, const std::vector<Moment>& moments, const Terrain& terrain,
                    const VehicleLayout& vehicle, const std::vector<uint32_t>& flag_triangles,
                    int panel_width, int panel_height, std::string* error);

}  // namespace vehicle_flag
