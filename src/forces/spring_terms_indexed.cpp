// IndexedSprings: springs of any mesh as (first, second) index pairs.
// Stage 1 is a loop over springs; the particle gathers walk the fabric's
// padded incidence slots (PaddedSlots), slot by slot over chunks of
// particles, so both vectorize (indexed loads, contiguous accumulators).
// Stage 1 also stores each spring's block at its two slots, so the
// products (many per substep) load blocks contiguously and gather only
// the other particle's x, not six block entries per slot as well
// (docs/measurements.md, "The mesh's products and spring kernels").
#include "base/lanes.h"
#include "forces/spring_terms.h"

namespace cloth {
namespace {

// The kernels take every array as a __restrict parameter: GCC trusts
// restrict on parameters (not on locals) and only then vectorizes the
// indexed loads.
// kCable: with the strain cable (springs.h).
template <bool kCable>
CLOTH_HOT_LOOP void evaluate_kernel(uint32_t begin, uint32_t end, float h, SpringModel model,
                                    const uint32_t* __restrict first, const uint32_t* __restrict second,
                                    const float* __restrict rest, const float* __restrict stiffness,
                                    const float* __restrict damping, const float* __restrict px,
                                    const float* __restrict py, const float* __restrict pz,
                                    const float* __restrict vx, const float* __restrict vy,
                                    const float* __restrict vz, float* __restrict fx, float* __restrict fy,
                                    float* __restrict fz, float* __restrict bxx, float* __restrict bxy,
                                    float* __restrict bxz, float* __restrict byy, float* __restrict byz,
                                    float* __restrict bzz) {
    for (uint32_t s = begin; s < end; ++s) {
        const uint32_t i = first[s], j = second[s];
        const SpringTerm t =
            spring_term<kCable>(px[j] - px[i], py[j] - py[i], pz[j] - pz[i], vx[j] - vx[i], vy[j] - vy[i],
                                vz[j] - vz[i], rest[s], stiffness[s], damping[s], h, model);
        fx[s] = t.fx;
        fy[s] = t.fy;
        fz[s] = t.fz;
        bxx[s] = t.bxx;
        bxy[s] = t.bxy;
        bxz[s] = t.bxz;
        byy[s] = t.byy;
        byz[s] = t.byz;
        bzz[s] = t.bzz;
    }
}

// One incidence slot (entry of particle i at base + i): f_i += sign * force_s.
CLOTH_HOT_LOOP void gather_kernel(uint32_t begin, uint32_t end, int64_t base,
                                  const uint32_t* __restrict spring, const float* __restrict sign,
                                  const float* __restrict sfx, const float* __restrict sfy,
                                  const float* __restrict sfz, float* __restrict fx, float* __restrict fy,
                                  float* __restrict fz) {
    for (uint32_t i = begin; i < end; ++i) {
        const uint32_t s = spring[base + i];
        const float g = sign[base + i];
        fx[i] += sfx[s] * g;
        fy[i] += sfy[s] * g;
        fz[i] += sfz[s] * g;
    }
}

// One incidence slot: w_i += A_s, and A_s copied to the slot (o at base + i)
// for the products, which then load it contiguously. Copied here, where
// the slot's block is loaded anyway, so no pass after evaluation scatters
// each spring's block to its two slots.
CLOTH_HOT_LOOP void gather_block_kernel(uint32_t begin, uint32_t end, int64_t base,
                                        const uint32_t* __restrict spring, const float* __restrict sxx,
                                        const float* __restrict sxy, const float* __restrict sxz,
                                        const float* __restrict syy, const float* __restrict syz,
                                        const float* __restrict szz, float* __restrict wxx,
                                        float* __restrict wxy, float* __restrict wxz, float* __restrict wyy,
                                        float* __restrict wyz, float* __restrict wzz, float* __restrict oxx,
                                        float* __restrict oxy, float* __restrict oxz, float* __restrict oyy,
                                        float* __restrict oyz, float* __restrict ozz) {
    for (uint32_t i = begin; i < end; ++i) {
        const int64_t k = base + i;
        const uint32_t s = spring[k];
        const float xx = sxx[s], xy = sxy[s], xz = sxz[s], yy = syy[s], yz = syz[s], zz = szz[s];
        wxx[i] += xx;
        wxy[i] += xy;
        wxz[i] += xz;
        wyy[i] += yy;
        wyz[i] += yz;
        wzz[i] += zz;
        oxx[k] = xx;
        oxy[k] = xy;
        oxz[k] = xz;
        oyy[k] = yy;
        oyz[k] = yz;
        ozz[k] = zz;
    }
}

// One incidence slot: q_i += A_s x_other, A_s stored at the slot.
CLOTH_HOT_LOOP void product_kernel(uint32_t begin, uint32_t end, int64_t base,
                                   const uint32_t* __restrict other, const float* __restrict sxx,
                                   const float* __restrict sxy, const float* __restrict sxz,
                                   const float* __restrict syy, const float* __restrict syz,
                                   const float* __restrict szz, const float* __restrict xx,
                                   const float* __restrict xy, const float* __restrict xz,
                                   float* __restrict qx, float* __restrict qy, float* __restrict qz) {
    for (uint32_t i = begin; i < end; ++i) {
        const int64_t s = base + i;
        const uint32_t o = other[s];
        const float ox = xx[o], oy = xy[o], oz = xz[o];
        qx[i] += sxx[s] * ox + sxy[s] * oy + sxz[s] * oz;
        qy[i] += sxy[s] * ox + syy[s] * oy + syz[s] * oz;
        qz[i] += sxz[s] * ox + syz[s] * oy + szz[s] * oz;
    }
}

class IndexedSprings final : public SpringTerms {
  public:
    IndexedSprings(const HostMemory* memory, std::shared_ptr<const Fabric> fabric, const Material& material)
        : fabric_(std::move(fabric)),
          stiffness_(HostAllocator<float>(memory)),
          damping_(HostAllocator<float>(memory)),
          force_(memory),
          block_(memory),
          slot_block_(memory) {
        const uint32_t count = fabric_->spring_count();
        stiffness_.resize(count);
        damping_.resize(count);
        // One zero entry past the end: the dummy spring padded slots point at.
        force_.resize(count + 1);
        block_.resize(count + 1);
        slot_block_.resize(fabric_->spring_slots.item.size());
        set_material(material);
    }

    void set_material(const Material& material) override {
        for (uint32_t s = 0; s < fabric_->spring_count(); ++s) {
            stiffness_[s] = material.springs[fabric_->spring_kind[s]].stiffness;
            damping_[s] = material.springs[fabric_->spring_kind[s]].damping;
        }
    }

    uint32_t item_count() const override { return fabric_->spring_count(); }

    void evaluate(const Vec3Soa& x, const Vec3Soa& v, float h, SpringModel model, uint32_t begin,
                  uint32_t end) override {
        const Fabric& f = *fabric_;
        const auto kernel = model.cable_factor > 0 ? evaluate_kernel<true> : evaluate_kernel<false>;
        kernel(begin, end, h, model, f.spring_first.data(), f.spring_second.data(),
               f.spring_rest_length.data(), stiffness_.data(), damping_.data(), x.x.data(), x.y.data(),
               x.z.data(), v.x.data(), v.y.data(), v.z.data(), force_.x.data(), force_.y.data(),
               force_.z.data(), block_.xx.data(), block_.xy.data(), block_.xz.data(), block_.yy.data(),
               block_.yz.data(), block_.zz.data());
    }

    void gather(uint32_t begin, uint32_t end, Vec3Soa& force, Sym3Soa* diagonal) const override {
        const PaddedSlots& slots = fabric_->spring_slots;
        slots.for_each_slot(
            fabric_->particle_count(), begin, end, [&](uint32_t lo, uint32_t hi, int64_t base, uint32_t) {
                gather_kernel(lo, hi, base, slots.item.data(), slots.sign.data(), force_.x.data(),
                              force_.y.data(), force_.z.data(), force.x.data(), force.y.data(),
                              force.z.data());
                if (!diagonal) return;
                gather_block_kernel(lo, hi, base, slots.item.data(), block_.xx.data(), block_.xy.data(),
                                    block_.xz.data(), block_.yy.data(), block_.yz.data(), block_.zz.data(),
                                    diagonal->xx.data(), diagonal->xy.data(), diagonal->xz.data(),
                                    diagonal->yy.data(), diagonal->yz.data(), diagonal->zz.data(),
                                    slot_block_.xx.data(), slot_block_.xy.data(), slot_block_.xz.data(),
                                    slot_block_.yy.data(), slot_block_.yz.data(), slot_block_.zz.data());
            });
    }

    void neighbour_sums(const Vec3Soa& x, uint32_t begin, uint32_t end, Vec3Soa& q) const override {
        const PaddedSlots& slots = fabric_->spring_slots;
        for (HostVector<float>* a : {&q.x, &q.y, &q.z}) std::fill(a->begin() + begin, a->begin() + end, 0.0f);
        slots.for_each_slot(
            fabric_->particle_count(), begin, end, [&](uint32_t lo, uint32_t hi, int64_t base, uint32_t) {
                product_kernel(lo, hi, base, slots.other.data(), slot_block_.xx.data(), slot_block_.xy.data(),
                               slot_block_.xz.data(), slot_block_.yy.data(), slot_block_.yz.data(),
                               slot_block_.zz.data(), x.x.data(), x.y.data(), x.z.data(), q.x.data(),
                               q.y.data(), q.z.data());
            });
    }

    void for_each_block(const std::function<void(uint32_t, uint32_t, const Sym3&)>& visit) const override {
        for (uint32_t s = 0; s < fabric_->spring_count(); ++s) {
            visit(fabric_->spring_first[s], fabric_->spring_second[s], block_.get(s));
        }
    }

    void sum_blocks(const float* pinned, const uint32_t* start, const uint32_t* spring, uint32_t begin,
                    uint32_t end, Sym3* out) const override {
        // The arrays read once, not per spring (a gather of the
        // multigrid's coarse operators, every substep).
        const uint32_t* first = fabric_->spring_first.data();
        const uint32_t* second = fabric_->spring_second.data();
        const float *xx = block_.xx.data(), *xy = block_.xy.data(), *xz = block_.xz.data();
        const float *yy = block_.yy.data(), *yz = block_.yz.data(), *zz = block_.zz.data();
        for (uint32_t t = begin; t < end; ++t) {
            Sym3 sum{};
            for (uint32_t k = start[t]; k < start[t + 1]; ++k) {
                const uint32_t s = spring[k];
                if (pinned[first[s]] != 0.0f || pinned[second[s]] != 0.0f) continue;
                sum.xx += xx[s];
                sum.xy += xy[s];
                sum.xz += xz[s];
                sum.yy += yy[s];
                sum.yz += yz[s];
                sum.zz += zz[s];
            }
            out[t] = sum;
        }
    }

  private:
    std::shared_ptr<const Fabric> fabric_;
    HostVector<float> stiffness_, damping_;  // per spring, from the material
    Vec3Soa force_;                          // per spring: f~ contribution on its first particle
    Sym3Soa block_;                          // per spring: A_s
    // A_s again at each of its incidence slots, laid out by the gather
    // with a diagonal (the products' contiguous copy; padding slots stay zero).
    mutable Sym3Soa slot_block_;
};

}  // namespace

std::shared_ptr<SpringTerms> make_indexed_springs(const HostMemory* memory,
                                                  std::shared_ptr<const Fabric> fabric,
                                                  const Material& material) {
    return std::allocate_shared<IndexedSprings>(HostAllocator<IndexedSprings>(memory), memory,
                                                std::move(fabric), material);
}

}  // namespace cloth
