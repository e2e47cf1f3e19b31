#include "linear_system.h"

#include <algorithm>

namespace cloth {
namespace {

// The gathers walk the fabric's padded incidence slots: for each slot k, a
// loop over a chunk of particles that the compiler vectorizes (indexed
// loads, contiguous accumulators). Chunks keep the accumulators in L1.
// Every array is a __restrict parameter so GCC vectorizes the indexed loads.
constexpr uint32_t kChunk = 256;

// f_i += sign * force_s and w_i += A_s over the incident springs of [begin, end).
void gather_springs_kernel(uint32_t begin, uint32_t end, size_t slot, const uint32_t* __restrict spring,
                           const float* __restrict sign, const float* __restrict sfx, const float* __restrict sfy,
                           const float* __restrict sfz, const float* __restrict sxx, const float* __restrict sxy,
                           const float* __restrict sxz, const float* __restrict syy, const float* __restrict syz,
                           const float* __restrict szz, float* __restrict fx, float* __restrict fy,
                           float* __restrict fz, float* __restrict wxx, float* __restrict wxy, float* __restrict wxz,
                           float* __restrict wyy, float* __restrict wyz, float* __restrict wzz) {
    for (uint32_t i = begin; i < end; ++i) {
        const uint32_t s = spring[slot + i];
        const float g = sign[slot + i];
        fx[i] += sfx[s] * g;
        fy[i] += sfy[s] * g;
        fz[i] += sfz[s] * g;
        wxx[i] += sxx[s];
        wxy[i] += sxy[s];
        wxz[i] += sxz[s];
        wyy[i] += syy[s];
        wyz[i] += syz[s];
        wzz[i] += szz[s];
    }
}

// q_i += A_s x_other over one slot of the incident springs of [begin, end).
void gather_products_kernel(uint32_t begin, uint32_t end, size_t slot, const uint32_t* __restrict spring,
                            const uint32_t* __restrict other, const float* __restrict sxx,
                            const float* __restrict sxy, const float* __restrict sxz, const float* __restrict syy,
                            const float* __restrict syz, const float* __restrict szz, const float* __restrict xx,
                            const float* __restrict xy, const float* __restrict xz, float* __restrict qx,
                            float* __restrict qy, float* __restrict qz) {
    for (uint32_t i = begin; i < end; ++i) {
        const uint32_t s = spring[slot + i], o = other[slot + i];
        const float ox = xx[o], oy = xy[o], oz = xz[o];
        qx[i] += sxx[s] * ox + sxy[s] * oy + sxz[s] * oz;
        qy[i] += sxy[s] * ox + syy[s] * oy + syz[s] * oz;
        qz[i] += sxz[s] * ox + syz[s] * oy + szz[s] * oz;
    }
}

// q_i = sum over the incident springs of A_s x_other, for [begin, end).
void neighbour_sums(const Fabric& f, const Sym3Soa& block, const Vec3Soa& x, uint32_t begin, uint32_t end,
                    Vec3Soa& q) {
    const size_t n = f.particle_count();
    std::fill(q.x.begin() + begin, q.x.begin() + end, 0.0f);
    std::fill(q.y.begin() + begin, q.y.begin() + end, 0.0f);
    std::fill(q.z.begin() + begin, q.z.begin() + end, 0.0f);
    for (uint32_t chunk = begin; chunk < end; chunk += kChunk) {
        const uint32_t chunk_end = std::min(end, chunk + kChunk);
        for (uint32_t k = 0; k < f.padded_spring_width; ++k) {
            gather_products_kernel(chunk, chunk_end, k * n, f.padded_spring.data(), f.padded_other.data(),
                                   block.xx.data(), block.xy.data(), block.xz.data(), block.yy.data(),
                                   block.yz.data(), block.zz.data(), x.x.data(), x.y.data(), x.z.data(),
                                   q.x.data(), q.y.data(), q.z.data());
        }
    }
}

}  // namespace

void assemble_particles(const AssemblyPass& pass, uint32_t begin, uint32_t end, Sym3Soa& diagonal,
                        Sym3Soa& diagonal_inverse, Vec3Soa& rhs, Vec3Soa& p) {
    const Fabric& f = *pass.fabric;
    const size_t n = f.particle_count();
    // rhs accumulates f~ (scaled by h at the end), diagonal accumulates W_ii.
    for (uint32_t i = begin; i < end; ++i) {
        rhs.set(i, pass.external_force->get(i));
        diagonal.set(i, Sym3::identity(pass.mass[i] * (1.0f + pass.h * pass.linear_drag)));
    }
    const Vec3Soa& sf = *pass.spring_force;
    const Sym3Soa& sb = *pass.spring_block;
    for (uint32_t chunk = begin; chunk < end; chunk += kChunk) {
        const uint32_t chunk_end = std::min(end, chunk + kChunk);
        for (uint32_t k = 0; k < f.padded_spring_width; ++k) {
            gather_springs_kernel(chunk, chunk_end, k * n, f.padded_spring.data(), f.padded_sign.data(),
                                  sf.x.data(), sf.y.data(), sf.z.data(), sb.xx.data(), sb.xy.data(), sb.xz.data(),
                                  sb.yy.data(), sb.yz.data(), sb.zz.data(), rhs.x.data(), rhs.y.data(),
                                  rhs.z.data(), diagonal.xx.data(), diagonal.xy.data(), diagonal.xz.data(),
                                  diagonal.yy.data(), diagonal.yz.data(), diagonal.zz.data());
        }
    }
    for (uint32_t i = begin; i < end; ++i) {
        const Vec3 b = rhs.get(i) * pass.h;
        rhs.set(i, b);
        const Sym3 inverse = pass.pinned[i] ? Sym3{} : diagonal.get(i).inverse();
        diagonal_inverse.set(i, inverse);
        p.set(i, inverse * b);
    }
}

void jacobi_sweep(const LinearSystem& system, const Vec3Soa& current, uint32_t begin, uint32_t end, Vec3Soa& next) {
    neighbour_sums(*system.fabric, *system.spring_block, current, begin, end, next);
    for (uint32_t i = begin; i < end; ++i) {
        next.set(i, system.diagonal_inverse->get(i) * (system.rhs->get(i) + next.get(i)));
    }
}

void multiply_system(const LinearSystem& system, const Vec3Soa& x, uint32_t begin, uint32_t end, Vec3Soa& y) {
    neighbour_sums(*system.fabric, *system.spring_block, x, begin, end, y);
    for (uint32_t i = begin; i < end; ++i) {
        y.set(i, system.pinned[i] ? Vec3::Zero() : Vec3(system.diagonal->get(i) * x.get(i) - y.get(i)));
    }
}

}  // namespace cloth
