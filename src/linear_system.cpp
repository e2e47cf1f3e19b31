#include "linear_system.h"

namespace cloth {

void assemble_particles(const AssemblyPass& pass, uint32_t begin, uint32_t end, Sym3Soa& diagonal,
                        Sym3Soa& diagonal_inverse, Vec3Soa& rhs, Vec3Soa& p) {
    // rhs accumulates f~ (scaled by h below), diagonal accumulates W_ii.
    for (uint32_t i = begin; i < end; ++i) {
        rhs.set(i, pass.external_force->get(i));
        diagonal.set(i, Sym3::identity(pass.mass[i] * (1.0f + pass.h * pass.linear_drag)));
    }
    pass.springs->gather(begin, end, rhs, &diagonal);
    for (uint32_t i = begin; i < end; ++i) {
        const Vec3 b = rhs.get(i) * pass.h;
        rhs.set(i, b);
        const Sym3 inverse = pass.pinned[i] ? Sym3{} : diagonal.get(i).inverse();
        diagonal_inverse.set(i, inverse);
        p.set(i, inverse * b);
    }
}

void jacobi_sweep(const LinearSystem& system, const Vec3Soa& current, uint32_t begin, uint32_t end, Vec3Soa& next) {
    system.springs->neighbour_sums(current, begin, end, next);
    for (uint32_t i = begin; i < end; ++i) {
        next.set(i, system.diagonal_inverse->get(i) * (system.rhs->get(i) + next.get(i)));
    }
}

void multiply_system(const LinearSystem& system, const Vec3Soa& x, uint32_t begin, uint32_t end, Vec3Soa& y) {
    system.springs->neighbour_sums(x, begin, end, y);
    for (uint32_t i = begin; i < end; ++i) {
        y.set(i, system.pinned[i] ? Vec3::Zero() : Vec3(system.diagonal->get(i) * x.get(i) - y.get(i)));
    }
}

}  // namespace cloth
