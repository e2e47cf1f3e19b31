#include "linear_system.h"

namespace cloth {

void assemble_particles(const AssemblyPass& pass, uint32_t begin, uint32_t end, Sym3* diagonal,
                        Sym3* diagonal_inverse, Vec3* rhs, Vec3* p) {
    const Fabric& f = *pass.fabric;
    for (uint32_t i = begin; i < end; ++i) {
        Vec3 force = pass.external_force[i];
        Sym3 w = Sym3::identity(pass.mass[i] * (1.0f + pass.h * pass.linear_drag));
        for (uint32_t e = f.incidence_offset[i]; e < f.incidence_offset[i + 1]; ++e) {
            const uint32_t s = f.incidence_spring[e];
            force += pass.spring_force[s] * f.incidence_sign[e];
            w += pass.spring_block[s];
        }
        diagonal[i] = w;
        rhs[i] = force * pass.h;
        if (pass.pinned[i]) {
            diagonal_inverse[i] = Sym3{};
            p[i].setZero();
        } else {
            diagonal_inverse[i] = w.inverse();
            p[i] = diagonal_inverse[i] * rhs[i];
        }
    }
}

void gather_neighbours(const LinearSystem& system, const Vec3* x, uint32_t begin, uint32_t end, Vec3* q) {
    const Fabric& f = *system.fabric;
    for (uint32_t i = begin; i < end; ++i) {
        Vec3 sum = Vec3::Zero();
        for (uint32_t e = f.incidence_offset[i]; e < f.incidence_offset[i + 1]; ++e) {
            sum += system.spring_block[f.incidence_spring[e]] * x[f.incidence_other[e]];
        }
        q[i] = sum;
    }
}

void multiply_system(const LinearSystem& system, const Vec3* x, uint32_t begin, uint32_t end, Vec3* y) {
    gather_neighbours(system, x, begin, end, y);
    for (uint32_t i = begin; i < end; ++i) {
        y[i] = system.pinned[i] ? Vec3::Zero() : Vec3(system.diagonal[i] * x[i] - y[i]);
    }
}

}  // namespace cloth
