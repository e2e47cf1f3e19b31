// What a cloth is made of: spring stiffness and damping per family, and mass.
#pragma once

#include <cstdint>

#include "fabric/fabric.h"

namespace cloth {

struct SpringParams {
    float stiffness = 0;  // N/m
    float damping = 0;    // N s/m
};

// The defaults here are the library's defaults; cloth_default_desc() and
// cloth_default_solver_settings() copy them.
struct Material {
    SpringParams springs[kSpringKindCount] = {{1000.0f, 0.5f}, {200.0f, 0.2f}, {20.0f, 0.05f}};
    float area_density = 0.2f;  // kg/m^2
    float particle_mass = 0;    // kg; > 0 overrides area_density
};

}  // namespace cloth
