// GridSprings: a regular grid's springs as families (fabric.h); family f
// joins particle p to p + offset_f. Per family the forces and blocks are
// stored by first particle, so every loop here is a plain range loop with
// contiguous loads: particle p reads its family-f spring as first particle
// at p and as second particle at p - offset_f. Entries past n - offset_f
// are never written and stay zero.
#include "spring_terms.h"

namespace cloth {
namespace {

// Every array is a __restrict parameter so GCC vectorizes the loops.
void evaluate_family_kernel(uint32_t begin, uint32_t end, uint32_t offset, float rest, float k, float c, float h,
                            JacobianClamp clamp, const float* __restrict mask, const float* __restrict px,
                            const float* __restrict py, const float* __restrict pz, const float* __restrict vx,
                            const float* __restrict vy, const float* __restrict vz, float* __restrict fx,
                            float* __restrict fy, float* __restrict fz, float* __restrict bxx, float* __restrict bxy,
                            float* __restrict bxz, float* __restrict byy, float* __restrict byz,
                            float* __restrict bzz) {
    for (uint32_t p = begin; p < end; ++p) {
        const uint32_t j = p + offset;
        // Where the family has no spring (grid edge) the mask zeroes k and c,
        // which zeroes the whole term.
        const SpringTerm t = spring_term(px[j] - px[p], py[j] - py[p], pz[j] - pz[p], vx[j] - vx[p], vy[j] - vy[p],
                                         vz[j] - vz[p], rest, k * mask[p], c * mask[p], h, clamp);
        fx[p] = t.fx;
        fy[p] = t.fy;
        fz[p] = t.fz;
        bxx[p] = t.bxx;
        bxy[p] = t.bxy;
        bxz[p] = t.bxz;
        byy[p] = t.byy;
        byz[p] = t.byz;
        bzz[p] = t.bzz;
    }
}

// f_p += sign * force[p - shift]
void gather_force_kernel(uint32_t begin, uint32_t end, uint32_t shift, float sign, const float* __restrict sfx,
                         const float* __restrict sfy, const float* __restrict sfz, float* __restrict fx,
                         float* __restrict fy, float* __restrict fz) {
    for (uint32_t p = begin; p < end; ++p) {
        fx[p] += sfx[p - shift] * sign;
        fy[p] += sfy[p - shift] * sign;
        fz[p] += sfz[p - shift] * sign;
    }
}

// w_p += A[p - shift]
void gather_block_kernel(uint32_t begin, uint32_t end, uint32_t shift, const float* __restrict sxx,
                         const float* __restrict sxy, const float* __restrict sxz, const float* __restrict syy,
                         const float* __restrict syz, const float* __restrict szz, float* __restrict wxx,
                         float* __restrict wxy, float* __restrict wxz, float* __restrict wyy, float* __restrict wyz,
                         float* __restrict wzz) {
    for (uint32_t p = begin; p < end; ++p) {
        wxx[p] += sxx[p - shift];
        wxy[p] += sxy[p - shift];
        wxz[p] += sxz[p - shift];
        wyy[p] += syy[p - shift];
        wyz[p] += syz[p - shift];
        wzz[p] += szz[p - shift];
    }
}

// q_p += A[p + block_shift] x[p + x_shift]
void product_kernel(uint32_t begin, uint32_t end, int64_t block_shift, int64_t x_shift, const float* __restrict sxx,
                    const float* __restrict sxy, const float* __restrict sxz, const float* __restrict syy,
                    const float* __restrict syz, const float* __restrict szz, const float* __restrict xx,
                    const float* __restrict xy, const float* __restrict xz, float* __restrict qx,
                    float* __restrict qy, float* __restrict qz) {
    for (uint32_t p = begin; p < end; ++p) {
        const int64_t s = p + block_shift, o = p + x_shift;
        const float ox = xx[o], oy = xy[o], oz = xz[o];
        qx[p] += sxx[s] * ox + sxy[s] * oy + sxz[s] * oz;
        qy[p] += sxy[s] * ox + syy[s] * oy + syz[s] * oz;
        qz[p] += sxz[s] * ox + syz[s] * oy + szz[s] * oz;
    }
}

struct FamilyTerms {
    explicit FamilyTerms(const HostMemory* memory) : force(memory), block(memory) {}
    Vec3Soa force;  // by first particle
    Sym3Soa block;
    float stiffness = 0, damping = 0;
};

class GridSprings final : public SpringTerms {
public:
    GridSprings(const HostMemory* memory, std::shared_ptr<const Fabric> fabric, const Material& material)
        : fabric_(std::move(fabric)), terms_(HostAllocator<FamilyTerms>(memory)) {
        const uint32_t n = fabric_->particle_count();
        for (size_t f = 0; f < fabric_->grid_families.size(); ++f) {
            FamilyTerms& t = terms_.emplace_back(memory);
            t.force.resize(n);
            t.block.resize(n);
        }
        set_material(material);
    }

    void set_material(const Material& material) override {
        for (size_t f = 0; f < terms_.size(); ++f) {
            terms_[f].stiffness = material.springs[fabric_->grid_families[f].kind].stiffness;
            terms_[f].damping = material.springs[fabric_->grid_families[f].kind].damping;
        }
    }

    uint32_t item_count() const override { return fabric_->particle_count(); }

    void evaluate(const Vec3Soa& x, const Vec3Soa& v, float h, JacobianClamp clamp, uint32_t begin,
                  uint32_t end) override {
        const uint32_t n = fabric_->particle_count();
        for (size_t f = 0; f < terms_.size(); ++f) {
            const SpringFamily& family = fabric_->grid_families[f];
            FamilyTerms& t = terms_[f];
            evaluate_family_kernel(begin, std::min(end, n - family.offset), family.offset, family.rest_length,
                                   t.stiffness, t.damping, h, clamp, family.mask.data(), x.x.data(), x.y.data(),
                                   x.z.data(), v.x.data(), v.y.data(), v.z.data(), t.force.x.data(),
                                   t.force.y.data(), t.force.z.data(), t.block.xx.data(), t.block.xy.data(),
                                   t.block.xz.data(), t.block.yy.data(), t.block.yz.data(), t.block.zz.data());
        }
    }

    void gather(uint32_t begin, uint32_t end, Vec3Soa& force, Sym3Soa* diagonal) const override {
        for (size_t f = 0; f < terms_.size(); ++f) {
            const uint32_t offset = fabric_->grid_families[f].offset;
            const FamilyTerms& t = terms_[f];
            // As first particle: +force[p]; as second: -force[p - offset].
            const uint32_t second_begin = std::max(begin, offset);
            gather_force_kernel(begin, end, 0, 1.0f, t.force.x.data(), t.force.y.data(), t.force.z.data(),
                                force.x.data(), force.y.data(), force.z.data());
            if (second_begin < end) {
                gather_force_kernel(second_begin, end, offset, -1.0f, t.force.x.data(), t.force.y.data(),
                                    t.force.z.data(), force.x.data(), force.y.data(), force.z.data());
            }
            if (!diagonal) continue;
            for (uint32_t shift : {0u, offset}) {
                const uint32_t from = std::max(begin, shift);
                if (from >= end) continue;
                gather_block_kernel(from, end, shift, t.block.xx.data(), t.block.xy.data(), t.block.xz.data(),
                                    t.block.yy.data(), t.block.yz.data(), t.block.zz.data(), diagonal->xx.data(),
                                    diagonal->xy.data(), diagonal->xz.data(), diagonal->yy.data(),
                                    diagonal->yz.data(), diagonal->zz.data());
            }
        }
    }

    void neighbour_sums(const Vec3Soa& x, uint32_t begin, uint32_t end, Vec3Soa& q) const override {
        const uint32_t n = fabric_->particle_count();
        for (HostVector<float>* a : {&q.x, &q.y, &q.z}) std::fill(a->begin() + begin, a->begin() + end, 0.0f);
        for (size_t f = 0; f < terms_.size(); ++f) {
            const int64_t offset = fabric_->grid_families[f].offset;
            const Sym3Soa& b = terms_[f].block;
            // As first particle: A[p] x[p + offset]; as second: A[p - offset] x[p - offset].
            const uint32_t first_end = std::min<uint32_t>(end, n - static_cast<uint32_t>(offset));
            if (begin < first_end) {
                product_kernel(begin, first_end, 0, offset, b.xx.data(), b.xy.data(), b.xz.data(), b.yy.data(),
                               b.yz.data(), b.zz.data(), x.x.data(), x.y.data(), x.z.data(), q.x.data(), q.y.data(),
                               q.z.data());
            }
            const uint32_t second_begin = std::max<uint32_t>(begin, static_cast<uint32_t>(offset));
            if (second_begin < end) {
                product_kernel(second_begin, end, -offset, -offset, b.xx.data(), b.xy.data(), b.xz.data(),
                               b.yy.data(), b.yz.data(), b.zz.data(), x.x.data(), x.y.data(), x.z.data(), q.x.data(),
                               q.y.data(), q.z.data());
            }
        }
    }

    void for_each_block(const std::function<void(uint32_t, uint32_t, const Sym3&)>& visit) const override {
        const uint32_t n = fabric_->particle_count();
        for (size_t f = 0; f < terms_.size(); ++f) {
            const SpringFamily& family = fabric_->grid_families[f];
            for (uint32_t p = 0; p + family.offset < n; ++p) {
                if (family.mask[p] != 0.0f) visit(p, p + family.offset, terms_[f].block.get(p));
            }
        }
    }

private:
    std::shared_ptr<const Fabric> fabric_;
    std::vector<FamilyTerms, HostAllocator<FamilyTerms>> terms_;
};

}  // namespace

std::shared_ptr<SpringTerms> make_spring_terms(const HostMemory* memory, std::shared_ptr<const Fabric> fabric,
                                               const Material& material) {
    if (fabric->grid_families.empty()) return make_indexed_springs(memory, std::move(fabric), material);
    return std::allocate_shared<GridSprings>(HostAllocator<GridSprings>(memory), memory, std::move(fabric),
                                             material);
}

}  // namespace cloth
