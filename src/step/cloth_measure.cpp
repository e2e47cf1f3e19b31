#include "step/cloth_measure.h"

#include <algorithm>
#include <cmath>

namespace cloth {

ClothMeasure measure(const ClothInstance& cloth, const Vec3& gravity) {
    const Fabric& f = cloth.fabric();
    const auto& x = cloth.positions();
    const auto& v = cloth.velocities();
    const auto& m = cloth.masses();
    ClothMeasure out;
    for (uint32_t i = 0; i < f.particle_count(); ++i) {
        const Vec3 vi = v.get(i);
        out.max_speed = std::max(out.max_speed, vi.norm());
        if (cloth.is_pinned(i)) continue;
        out.kinetic_energy += 0.5 * m[i] * static_cast<double>(vi.squaredNorm());
        out.gravity_energy -= m[i] * static_cast<double>(gravity.dot(x.get(i)));
    }
    double strain_sum = 0;
    uint32_t structural = 0;
    const SpringModel model = cloth.spring_model();
    for (uint32_t s = 0; s < f.spring_count(); ++s) {
        const float rest = f.spring_rest_length[s];
        const double length = (x.get(f.spring_second[s]) - x.get(f.spring_first[s])).norm();
        const double stretch = length - rest;
        const double k = cloth.material().springs[f.spring_kind[s]].stiffness;
        out.elastic_energy += 0.5 * k * stretch * stretch;
        // The strain cable's energy while it is taut (springs.h).
        const double cable_stretch = length - static_cast<double>(model.cable_stretch) * rest;
        if (model.cable_factor > 0 && cable_stretch > 0)
            out.elastic_energy += 0.5 * k * model.cable_factor * cable_stretch * cable_stretch;
        if (f.spring_kind[s] != kStructural) continue;
        const float strain = static_cast<float>(stretch / rest);
        out.max_strain = structural == 0 ? strain : std::max(out.max_strain, strain);
        strain_sum += std::fabs(strain);
        out.max_abs_strain = std::max(out.max_abs_strain, std::fabs(strain));
        ++structural;
    }
    out.mean_strain = structural ? static_cast<float>(strain_sum / structural) : 0.0f;
    return out;
}

}  // namespace cloth
