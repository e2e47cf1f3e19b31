#include "linear_system.h"

namespace cloth {

void assemble_particles(const AssemblyPass& pass, uint32_t begin, uint32_t end, Sym3Soa& diagonal,
                        Sym3Soa& diagonal_inverse, Vec3Soa& rhs, Vec3Soa& p) {
    const Fabric& f = *pass.fabric;
    const uint32_t* __restrict offset = f.incidence_offset.data();
    const uint32_t* __restrict spring = f.incidence_spring.data();
    const float* __restrict sign = f.incidence_sign.data();
    const Vec3Soa& sf = *pass.spring_force;
    const Sym3Soa& sb = *pass.spring_block;
    for (uint32_t i = begin; i < end; ++i) {
        float fx = pass.external_force->x[i], fy = pass.external_force->y[i], fz = pass.external_force->z[i];
        Sym3 w = Sym3::identity(pass.mass[i] * (1.0f + pass.h * pass.linear_drag));
        for (uint32_t e = offset[i]; e < offset[i + 1]; ++e) {
            const uint32_t s = spring[e];
            fx += sf.x[s] * sign[e];
            fy += sf.y[s] * sign[e];
            fz += sf.z[s] * sign[e];
            w.xx += sb.xx[s];
            w.xy += sb.xy[s];
            w.xz += sb.xz[s];
            w.yy += sb.yy[s];
            w.yz += sb.yz[s];
            w.zz += sb.zz[s];
        }
        const Vec3 b(fx * pass.h, fy * pass.h, fz * pass.h);
        diagonal.set(i, w);
        rhs.set(i, b);
        const Sym3 inverse = pass.pinned[i] ? Sym3{} : w.inverse();
        diagonal_inverse.set(i, inverse);
        p.set(i, inverse * b);
    }
}

namespace {

// sum over the incident springs of particle i of A_s x_other.
inline Vec3 neighbour_sum(const Fabric& f, const Sym3Soa& block, const Vec3Soa& x, uint32_t i) {
    float sx = 0, sy = 0, sz = 0;
    for (uint32_t e = f.incidence_offset[i]; e < f.incidence_offset[i + 1]; ++e) {
        const uint32_t s = f.incidence_spring[e], o = f.incidence_other[e];
        const float ox = x.x[o], oy = x.y[o], oz = x.z[o];
        sx += block.xx[s] * ox + block.xy[s] * oy + block.xz[s] * oz;
        sy += block.xy[s] * ox + block.yy[s] * oy + block.yz[s] * oz;
        sz += block.xz[s] * ox + block.yz[s] * oy + block.zz[s] * oz;
    }
    return {sx, sy, sz};
}

}  // namespace

void jacobi_sweep(const LinearSystem& system, const Vec3Soa& current, uint32_t begin, uint32_t end, Vec3Soa& next) {
    const Fabric& f = *system.fabric;
    for (uint32_t i = begin; i < end; ++i) {
        const Vec3 q = neighbour_sum(f, *system.spring_block, current, i);
        next.set(i, system.diagonal_inverse->get(i) * (system.rhs->get(i) + q));
    }
}

void multiply_system(const LinearSystem& system, const Vec3Soa& x, uint32_t begin, uint32_t end, Vec3Soa& y) {
    const Fabric& f = *system.fabric;
    for (uint32_t i = begin; i < end; ++i) {
        const Vec3 q = neighbour_sum(f, *system.spring_block, x, i);
        y.set(i, system.pinned[i] ? Vec3::Zero() : Vec3(system.diagonal->get(i) * x.get(i) - q));
    }
}

}  // namespace cloth
