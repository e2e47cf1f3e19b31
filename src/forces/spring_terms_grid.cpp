// GridSprings: a regular grid's springs as families (fabric.h); family f
// joins particle p to p + offset_f. Per family the forces and blocks are
// stored by first particle, so every loop here has contiguous loads only:
// particle p reads its family-f spring as first particle at p and as second
// particle at p - offset_f. Entries past n - offset_f are never written and
// stay zero, and so do max_offset leading entries before p = 0, so p - offset_f
// reads a zero spring for p < offset_f instead of needing a test. The per-spring loop is vectorized by the
// compiler; the force and diagonal gather sums all families in registers, eight particles at a time
// (lanes.h); the products gather goes family by family over L1-sized chunks, which vectorizes best.
#include <cassert>
#include <type_traits>

#include "base/lanes.h"
#include "forces/grid_products.h"
#include "forces/spring_terms.h"

namespace cloth {
namespace {

// Every array is a __restrict parameter so GCC vectorizes the loops.
// kCable: with the strain cable (springs.h).
template <bool kCable>
CLOTH_HOT_LOOP void evaluate_family_kernel(
    uint32_t begin, uint32_t end, uint32_t offset, float k, float c, float h, SpringModel model,
    const float* __restrict mask, const float* __restrict rest, const float* __restrict px,
    const float* __restrict py, const float* __restrict pz, const float* __restrict vx,
    const float* __restrict vy, const float* __restrict vz, float* __restrict fx, float* __restrict fy,
    float* __restrict fz, float* __restrict bxx, float* __restrict bxy, float* __restrict bxz,
    float* __restrict byy, float* __restrict byz, float* __restrict bzz) {
    // 64-bit indices: with j = p + offset in 32 bits (which could wrap) GCC
    // loads the second ends lane by lane instead of as one vector.
    for (size_t p = begin; p < end; ++p) {
        const size_t j = p + offset;
        // Where the family has no spring (grid edge) the mask zeroes k and c,
        // which zeroes the whole term.
        const SpringTerm t =
            spring_term<kCable>(px[j] - px[p], py[j] - py[p], pz[j] - pz[p], vx[j] - vx[p], vy[j] - vy[p],
                                vz[j] - vz[p], rest[p], k * mask[p], c * mask[p], h, model);
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

// q_p += A[p + block_shift] x[p + x_shift]; every array a __restrict
// parameter so GCC vectorizes the loop.
CLOTH_HOT_LOOP void product_kernel(uint32_t begin, uint32_t end, int64_t block_shift, int64_t x_shift,
                                   const float* __restrict sxx, const float* __restrict sxy,
                                   const float* __restrict sxz, const float* __restrict syy,
                                   const float* __restrict syz, const float* __restrict szz,
                                   const float* __restrict xx, const float* __restrict xy,
                                   const float* __restrict xz, float* __restrict qx, float* __restrict qy,
                                   float* __restrict qz) {
    for (uint32_t p = begin; p < end; ++p) {
        const int64_t s = p + block_shift, o = p + x_shift;
        const float ox = xx[o], oy = xy[o], oz = xz[o];
        qx[p] += sxx[s] * ox + sxy[s] * oy + sxz[s] * oz;
        qy[p] += sxy[s] * ox + syy[s] * oy + syz[s] * oz;
        qz[p] += sxz[s] * ox + syz[s] * oy + szz[s] * oz;
    }
}

// Particles per chunk of neighbour_sums: its accumulators stay in L1.
constexpr uint32_t kChunk = 512;

}  // namespace

void grid_neighbour_sums(const GridBlocks& grid, const Vec3Soa& x, uint32_t begin, uint32_t end, Vec3Soa& q) {
    const uint32_t n = grid.n, pad = grid.pad;
    for (HostVector<float>* a : {&q.x, &q.y, &q.z}) std::fill(a->begin() + begin, a->begin() + end, 0.0f);
    for (uint32_t chunk = begin; chunk < end; chunk += kChunk) {
        const uint32_t chunk_end = std::min(end, chunk + kChunk);
        for (uint32_t f = 0; f < grid.family_count; ++f) {
            const uint32_t offset = grid.offsets[f];
            const Sym3Soa& block = *grid.blocks[f];
            const float* b[6] = {block.xx.data() + pad, block.xy.data() + pad, block.xz.data() + pad,
                                 block.yy.data() + pad, block.yz.data() + pad, block.zz.data() + pad};
            // As first particle: A[p] x[p + offset]; as second: A[p - offset] x[p - offset].
            const uint32_t first_end = std::min(chunk_end, n > offset ? n - offset : 0u);
            if (chunk < first_end) {
                product_kernel(chunk, first_end, 0, offset, b[0], b[1], b[2], b[3], b[4], b[5], x.x.data(),
                               x.y.data(), x.z.data(), q.x.data(), q.y.data(), q.z.data());
            }
            const uint32_t second_begin = std::max(chunk, offset);
            if (second_begin < chunk_end) {
                const int64_t back = -static_cast<int64_t>(offset);
                product_kernel(second_begin, chunk_end, back, back, b[0], b[1], b[2], b[3], b[4], b[5],
                               x.x.data(), x.y.data(), x.z.data(), q.x.data(), q.y.data(), q.z.data());
            }
        }
    }
}

namespace {

struct FamilyTerms {
    explicit FamilyTerms(const HostMemory* memory) : force(memory), block(memory) {}
    // By first particle, after max_offset zero entries: particle p is at
    // index max_offset + p.
    Vec3Soa force;
    Sym3Soa block;
    float stiffness = 0, damping = 0;
};

// force_p += sum over families of force[p] - force[p - offset] and, unless
// diagonal is null, diagonal_p += A[p] + A[p - offset]: all families summed
// in registers, eight particles at a time, in the same order whatever the
// range. For p < offset the leading zero entries stand in for the missing
// spring: x - (+0) is x, and x + (+0) is x for every sum here (they start
// from +0 or a mass, so they are never -0).
template <class Count>
__attribute__((always_inline)) inline void gather_families_impl(uint32_t begin, uint32_t end, uint32_t n,
                                                                uint32_t pad, const uint32_t* offsets,
                                                                const FamilyTerms* terms, Count family_count,
                                                                Vec3Soa& force, Sym3Soa* diagonal) {
    for_each_lane_group(begin, end, begin, n, [&](auto lanes, uint32_t p) {
        using L = decltype(lanes);
        using T = typename L::type;
        const uint32_t i = pad + p;
        T fx = L::load(&force.x[p]), fy = L::load(&force.y[p]), fz = L::load(&force.z[p]);
        for (uint32_t f = 0; f < family_count; ++f) {
            const Vec3Soa& t = terms[f].force;
            const uint32_t s = i - offsets[f];
            fx += L::load(&t.x[i]);
            fy += L::load(&t.y[i]);
            fz += L::load(&t.z[i]);
            fx -= L::load(&t.x[s]);
            fy -= L::load(&t.y[s]);
            fz -= L::load(&t.z[s]);
        }
        store_vec3<L>(force, p, fx, fy, fz);
        if (!diagonal) return;
        Sym3Lanes<L> w = load_sym3<L>(*diagonal, p);
        for (uint32_t f = 0; f < family_count; ++f) {
            const Sym3Soa& b = terms[f].block;
            for (uint32_t shift : {0u, offsets[f]}) {
                const uint32_t s = i - shift;
                w.xx += L::load(&b.xx[s]);
                w.xy += L::load(&b.xy[s]);
                w.xz += L::load(&b.xz[s]);
                w.yy += L::load(&b.yy[s]);
                w.yz += L::load(&b.yz[s]);
                w.zz += L::load(&b.zz[s]);
            }
        }
        store_sym3(*diagonal, p, w);
    });
}

// The usual grid has all six families: a compile-time count lets the
// compiler unroll the family loops.
CLOTH_HOT_LOOP void gather_families(uint32_t begin, uint32_t end, uint32_t n, uint32_t pad,
                                    const uint32_t* offsets, const FamilyTerms* terms, uint32_t family_count,
                                    Vec3Soa& force, Sym3Soa* diagonal) {
    if (family_count == 6) {
        gather_families_impl(begin, end, n, pad, offsets, terms, std::integral_constant<uint32_t, 6>{}, force,
                             diagonal);
    } else {
        gather_families_impl(begin, end, n, pad, offsets, terms, family_count, force, diagonal);
    }
}

class GridSprings final : public SpringTerms {
  public:
    GridSprings(const HostMemory* memory, std::shared_ptr<const Fabric> fabric, const Material& material)
        : fabric_(std::move(fabric)),
          terms_(HostAllocator<FamilyTerms>(memory)),
          offsets_(HostAllocator<uint32_t>(memory)),
          blocks_(HostAllocator<const Sym3Soa*>(memory)),
          spring_family_(HostAllocator<uint8_t>(memory)),
          spring_particle_(HostAllocator<uint32_t>(memory)) {
        const uint32_t n = fabric_->particle_count();
        terms_.reserve(fabric_->grid_families.size());
        for (const SpringFamily& family : fabric_->grid_families) {
            offsets_.push_back(family.offset);
            max_offset_ = std::max(max_offset_, family.offset);
        }
        for (size_t f = 0; f < fabric_->grid_families.size(); ++f) {
            FamilyTerms& t = terms_.emplace_back(memory);
            t.force.resize(max_offset_ + n);
            t.block.resize(max_offset_ + n);
        }
        for (const FamilyTerms& t : terms_) blocks_.push_back(&t.block);
        for (size_t f = 0; f < fabric_->grid_families.size(); ++f) {  // for_each_block's order
            const SpringFamily& family = fabric_->grid_families[f];
            for (uint32_t p = 0; p + family.offset < n; ++p) {
                if (family.mask[p] == 0.0f) continue;
                spring_family_.push_back(static_cast<uint8_t>(f));
                spring_particle_.push_back(p);
            }
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

    void evaluate(const Vec3Soa& x, const Vec3Soa& v, float h, SpringModel model, uint32_t begin,
                  uint32_t end) override {
        const uint32_t n = fabric_->particle_count(), pad = max_offset_;
        const auto kernel =
            model.cable_factor > 0 ? evaluate_family_kernel<true> : evaluate_family_kernel<false>;
        for (size_t f = 0; f < terms_.size(); ++f) {
            const SpringFamily& family = fabric_->grid_families[f];
            FamilyTerms& t = terms_[f];
            kernel(begin, std::min(end, n - family.offset), family.offset, t.stiffness, t.damping, h, model,
                   family.mask.data(), family.rest_length.data(), x.x.data(), x.y.data(), x.z.data(),
                   v.x.data(), v.y.data(), v.z.data(), t.force.x.data() + pad, t.force.y.data() + pad,
                   t.force.z.data() + pad, t.block.xx.data() + pad, t.block.xy.data() + pad,
                   t.block.xz.data() + pad, t.block.yy.data() + pad, t.block.yz.data() + pad,
                   t.block.zz.data() + pad);
        }
    }

    void gather(uint32_t begin, uint32_t end, Vec3Soa& force, Sym3Soa* diagonal) const override {
        gather_families(begin, end, fabric_->particle_count(), max_offset_, offsets_.data(), terms_.data(),
                        static_cast<uint32_t>(terms_.size()), force, diagonal);
    }

    void neighbour_sums(const Vec3Soa& x, uint32_t begin, uint32_t end, Vec3Soa& q) const override {
        const GridBlocks grid{fabric_->particle_count(), max_offset_, static_cast<uint32_t>(terms_.size()),
                              offsets_.data(), blocks_.data()};
        grid_neighbour_sums(grid, x, begin, end, q);
    }

    void for_each_block(const std::function<void(uint32_t, uint32_t, const Sym3&)>& visit) const override {
        const uint32_t n = fabric_->particle_count();
        for (size_t f = 0; f < terms_.size(); ++f) {
            const SpringFamily& family = fabric_->grid_families[f];
            for (uint32_t p = 0; p + family.offset < n; ++p) {
                if (family.mask[p] != 0.0f) visit(p, p + family.offset, terms_[f].block.get(max_offset_ + p));
            }
        }
    }

    void sum_blocks(const float* pinned, const uint32_t* start, const uint32_t* spring, uint32_t begin,
                    uint32_t end, Sym3* out) const override {
        // Each family's arrays and offset read once, not per spring (a
        // gather of the multigrid's coarse operators, every substep).
        constexpr uint32_t kMaxFamilies = 8;
        const uint32_t families = static_cast<uint32_t>(terms_.size());
        assert(families <= kMaxFamilies);
        const float* xx[kMaxFamilies]{};
        const float* xy[kMaxFamilies]{};
        const float* xz[kMaxFamilies]{};
        const float* yy[kMaxFamilies]{};
        const float* yz[kMaxFamilies]{};
        const float* zz[kMaxFamilies]{};
        uint32_t offset[kMaxFamilies]{};
        for (uint32_t f = 0; f < families && f < kMaxFamilies; ++f) {
            const Sym3Soa& b = terms_[f].block;
            xx[f] = b.xx.data() + max_offset_;
            xy[f] = b.xy.data() + max_offset_;
            xz[f] = b.xz.data() + max_offset_;
            yy[f] = b.yy.data() + max_offset_;
            yz[f] = b.yz.data() + max_offset_;
            zz[f] = b.zz.data() + max_offset_;
            offset[f] = offsets_[f];
        }
        const uint8_t* family_of = spring_family_.data();
        const uint32_t* particle_of = spring_particle_.data();
        for (uint32_t t = begin; t < end; ++t) {
            Sym3 sum{};
            for (uint32_t k = start[t]; k < start[t + 1]; ++k) {
                const uint32_t f = family_of[spring[k]], p = particle_of[spring[k]];
                if (pinned[p] != 0.0f || pinned[p + offset[f]] != 0.0f) continue;
                sum.xx += xx[f][p];
                sum.xy += xy[f][p];
                sum.xz += xz[f][p];
                sum.yy += yy[f][p];
                sum.yz += yz[f][p];
                sum.zz += zz[f][p];
            }
            out[t] = sum;
        }
    }

  private:
    std::shared_ptr<const Fabric> fabric_;
    std::vector<FamilyTerms, HostAllocator<FamilyTerms>> terms_;
    HostVector<uint32_t> offsets_;       // per family
    HostVector<const Sym3Soa*> blocks_;  // per family: &terms_[f].block
    // Per spring, in for_each_block's order: its family and first particle.
    HostVector<uint8_t> spring_family_;
    HostVector<uint32_t> spring_particle_;
    uint32_t max_offset_ = 0;
};

}  // namespace

std::shared_ptr<SpringTerms> make_spring_terms(const HostMemory* memory, std::shared_ptr<const Fabric> fabric,
                                               const Material& material) {
    if (fabric->grid_families.empty()) return make_indexed_springs(memory, std::move(fabric), material);
    return std::allocate_shared<GridSprings>(HostAllocator<GridSprings>(memory), memory, std::move(fabric),
                                             material);
}

}  // namespace cloth
