// Energy and strain of a cloth's current state, for stats, tests and the
// benchmarks' accuracy figures.
#pragma once

#include "step/cloth_instance.h"

namespace cloth {

struct ClothMeasure {
    double kinetic_energy = 0;  // J, free particles
    double gravity_energy = 0;  // J, -m g . x summed over free particles
    double elastic_energy = 0;  // J, k (L - l0)^2 / 2 over all springs, plus taut strain
                                // cables under the model of the cloth's last step
    float max_strain = 0;       // max (L - l0) / l0 over structural springs
    float mean_strain = 0;      // mean |L - l0| / l0 over structural springs
    float max_abs_strain = 0;   // max |L - l0| / l0 over structural springs
    float max_speed = 0;        // m/s over all particles

    double total_energy() const { return kinetic_energy + gravity_energy + elastic_energy; }
};

ClothMeasure measure(const ClothInstance& cloth, const Vec3& gravity);

}  // namespace cloth
