// Multigrid's per-substep work (multigrid.h): the coarse operators from the
// assembled system, and one application of the preconditioner (the fine
// passes and the V-cycle over the coarse levels). The levels are built in
// multigrid_levels.cpp.
#include "solve/multigrid.h"

#include <algorithm>
#include <cmath>

#include "base/lanes.h"

namespace cloth {
namespace {

// The block-diagonal passes of a smoothing sweep, lanes at a time (the
// fine level's and the coarse levels' alike).

// x = w D^-1 b over [begin, end) (`inverse` holds D^-1).
CLOTH_HOT_LOOP void smooth_from_zero_pass(const Sym3Soa& inverse, const Vec3Soa& b, uint32_t begin,
                                          uint32_t end, Vec3Soa& x) {
    const float w = Multigrid::kSmootherWeight;
    for_each_lane_group(begin, end, begin, end, [&](auto lanes, uint32_t i) {
        using L = decltype(lanes);
        typename L::type ox, oy, oz;
        sym3_times<L>(inverse, i, L::load(&b.x[i]) * w, L::load(&b.y[i]) * w, L::load(&b.z[i]) * w, ox, oy,
                      oz);
        store_vec3<L>(x, i, ox, oy, oz);
    });
}

// x += w D^-1 (b - y) over [begin, end).
CLOTH_HOT_LOOP void smooth_pass(const Sym3Soa& inverse, const Vec3Soa& b, const Vec3Soa& y, uint32_t begin,
                                uint32_t end, Vec3Soa& x) {
    const float w = Multigrid::kSmootherWeight;
    for_each_lane_group(begin, end, begin, end, [&](auto lanes, uint32_t i) {
        using L = decltype(lanes);
        typename L::type ox, oy, oz;
        sym3_times<L>(inverse, i, (L::load(&b.x[i]) - L::load(&y.x[i])) * w,
                      (L::load(&b.y[i]) - L::load(&y.y[i])) * w, (L::load(&b.z[i]) - L::load(&y.z[i])) * w,
                      ox, oy, oz);
        store_vec3<L>(x, i, L::load(&x.x[i]) + ox, L::load(&x.y[i]) + oy, L::load(&x.z[i]) + oz);
    });
}

// y += D x over [begin, end).
CLOTH_HOT_LOOP void add_block_product(const Sym3Soa& d, const Vec3Soa& x, uint32_t begin, uint32_t end,
                                      Vec3Soa& y) {
    for_each_lane_group(begin, end, begin, end, [&](auto lanes, uint32_t i) {
        using L = decltype(lanes);
        typename L::type ox, oy, oz;
        sym3_times<L>(d, i, L::load(&x.x[i]), L::load(&x.y[i]), L::load(&x.z[i]), ox, oy, oz);
        store_vec3<L>(y, i, L::load(&y.x[i]) + ox, L::load(&y.y[i]) + oy, L::load(&y.z[i]) + oz);
    });
}

}  // namespace

void Multigrid::assemble(const LinearSystem& system) {
    assemble_top(system, GroupTask{0, 1, 0, system.particle_count});
    assemble_coarse();
}

void Multigrid::assemble_top(const LinearSystem& system, const GroupTask& task) {
    if (levels_.empty()) return;
    // W_IJ = minus the springs between the two aggregates; W_II = the sum
    // of the free children's W_ii minus twice the springs inside the
    // aggregate. Gathers over lists in a fixed order: the same sums for
    // any split of the pairs and nodes over tasks.
    Level& top = levels_.front();
    const uint32_t pairs = static_cast<uint32_t>(top.pair_first.size());
    uint32_t begin, end;
    uint32_t pair_begin, pair_end;
    task.items(pairs, pair_begin, pair_end);
    system.springs->sum_blocks(system.pinned, target_start_.data(), target_spring_.data(), pair_begin,
                               pair_end, top.pair_block.data());
    for (uint32_t p = pair_begin; p < pair_end; ++p) top.pair_block[p] = top.pair_block[p] * -1.0f;
    task.items(top.size, begin, end);
    system.springs->sum_blocks(system.pinned, target_start_.data() + pairs, target_spring_.data(), begin, end,
                               inner_.data());
    for (uint32_t node = begin; node < end; ++node) {
        Sym3 d{};
        for (uint32_t k = child_start_[node]; k < child_start_[node + 1]; ++k) {
            const uint32_t i = child_[k];
            if (system.pinned[i] == 0.0f) d += system.diagonal->get(i);
        }
        top.diagonal[node] = d + inner_[node] * -2.0f;
    }
    spread_blocks(top, pair_begin, pair_end, begin, end);
}

void Multigrid::assemble_coarse() {
    if (levels_.empty()) return;
    // Each coarser level from the one above it.
    for (size_t l = 0; l + 1 < levels_.size(); ++l) {
        const Level& finer = levels_[l];
        Level& level = levels_[l + 1];
        const uint32_t level_pairs = static_cast<uint32_t>(level.pair_first.size());
        std::fill(level.diagonal.begin(), level.diagonal.end(), Sym3{});
        std::fill(level.pair_block.begin(), level.pair_block.end(), Sym3{});
        for (uint32_t node = 0; node < finer.size; ++node)
            level.diagonal[finer.aggregate[node]] += finer.diagonal[node];
        for (uint32_t p = 0; p < finer.pair_first.size(); ++p) {
            const uint32_t target = finer.pair_target[p];
            if (target < level_pairs) {
                level.pair_block[target] += finer.pair_block[p];
            } else {
                level.diagonal[target - level_pairs] += finer.pair_block[p] * 2.0f;
            }
        }
    }
    // Nodes with no free particle have a zero diagonal: they stay zero.
    for (size_t l = 1; l < levels_.size(); ++l) {
        Level& level = levels_[l];
        spread_blocks(level, 0, static_cast<uint32_t>(level.pair_first.size()), 0, level.size);
    }
    factor_coarsest();
}

// The layouts the cycle's passes read: a grid level's pair blocks by family
// (the entries of no pair stay zero from plan), the diagonal blocks and
// their inverses as arrays (zero where no particle is free).
void Multigrid::spread_blocks(Level& level, uint32_t pair_begin, uint32_t pair_end, uint32_t node_begin,
                              uint32_t node_end) {
    if (!level.pair_family.empty()) {
        for (uint32_t p = pair_begin; p < pair_end; ++p) {
            level.family_block[level.pair_family[p]].set(level.family_pad + level.pair_first[p],
                                                         level.pair_block[p]);
        }
    }
    for (uint32_t node = node_begin; node < node_end; ++node) {
        const Sym3& d = level.diagonal[node];
        level.diagonal_blocks.set(node, d);
        level.inverse.set(node, d.xx + d.yy + d.zz > 0.0f ? d.inverse() : Sym3{});
    }
}

// Cholesky of the coarsest level in place (lower triangle), nodes with no
// free particle kept as identity rows. Symmetric positive definite as a
// Galerkin product of W; a failed pivot (round-off) falls back to one
// block-Jacobi solve there.
void Multigrid::factor_coarsest() {
    const Level& level = levels_.back();
    const size_t m = 3 * size_t{level.size};
    double* a = coarsest_.data();
    std::fill(coarsest_.begin(), coarsest_.end(), 0.0);
    const auto put = [&](uint32_t row_node, uint32_t column_node, const Sym3& b) {
        const double e[3][3] = {{b.xx, b.xy, b.xz}, {b.xy, b.yy, b.yz}, {b.xz, b.yz, b.zz}};
        for (int r = 0; r < 3; ++r) {
            for (int c = 0; c < 3; ++c) a[(3 * row_node + r) * m + 3 * column_node + c] += e[r][c];
        }
    };
    for (uint32_t node = 0; node < level.size; ++node) {
        const Sym3& d = level.diagonal[node];
        put(node, node, d.xx + d.yy + d.zz > 0.0f ? d : Sym3::identity(1.0f));
    }
    for (size_t p = 0; p < level.pair_first.size(); ++p) {
        put(level.pair_first[p], level.pair_second[p], level.pair_block[p]);
        put(level.pair_second[p], level.pair_first[p], level.pair_block[p]);
    }
    coarsest_factored_ = true;
    for (size_t j = 0; j < m && coarsest_factored_; ++j) {
        double pivot = a[j * m + j];
        for (size_t k = 0; k < j; ++k) pivot -= a[j * m + k] * a[j * m + k];
        if (!(pivot > 0.0)) {
            coarsest_factored_ = false;
            break;
        }
        const double root = std::sqrt(pivot);
        a[j * m + j] = root;
        for (size_t i = j + 1; i < m; ++i) {
            double sum = a[i * m + j];
            for (size_t k = 0; k < j; ++k) sum -= a[i * m + k] * a[j * m + k];
            a[i * m + j] = sum / root;
        }
    }
}

void Multigrid::multiply(const Level& level, const Vec3Soa& x, Vec3Soa& y) const {
    if (!level.pair_family.empty()) {
        const GridBlocks grid{level.size, level.family_pad, 4, level.family_offset.data(),
                              level.family_block_pointer.data()};
        grid_neighbour_sums(grid, x, 0, level.size, y);
    } else {
        for (uint32_t node = 0; node < level.size; ++node) {
            Vec3 sum = Vec3::Zero();
            for (uint32_t k = level.row_start[node]; k < level.row_start[node + 1]; ++k) {
                sum += level.pair_block[level.row_pair[k]] * x.get(level.row_column[k]);
            }
            y.set(node, sum);
        }
    }
    add_block_product(level.diagonal_blocks, x, 0, level.size, y);
}

void Multigrid::cycle(uint32_t index) {
    Level& level = levels_[index];
    if (index + 1 == levels_.size()) {
        if (!coarsest_factored_) {
            for (uint32_t node = 0; node < level.size; ++node) {
                level.x.set(node, level.inverse.get(node) * level.rhs.get(node));
            }
            return;
        }
        // L L^T x = rhs by two triangular solves.
        const size_t m = 3 * size_t{level.size};
        const double* a = coarsest_.data();
        double* v = coarsest_vector_.data();
        for (uint32_t node = 0; node < level.size; ++node) {
            v[3 * node] = level.rhs.x[node];
            v[3 * node + 1] = level.rhs.y[node];
            v[3 * node + 2] = level.rhs.z[node];
        }
        for (size_t i = 0; i < m; ++i) {
            for (size_t k = 0; k < i; ++k) v[i] -= a[i * m + k] * v[k];
            v[i] /= a[i * m + i];
        }
        for (size_t i = m; i-- > 0;) {
            for (size_t k = i + 1; k < m; ++k) v[i] -= a[k * m + i] * v[k];
            v[i] /= a[i * m + i];
        }
        for (uint32_t node = 0; node < level.size; ++node) {
            const Sym3& d = level.diagonal[node];
            const bool free = d.xx + d.yy + d.zz > 0.0f;
            level.x.set(node, free
                                  ? Vec3(static_cast<float>(v[3 * node]), static_cast<float>(v[3 * node + 1]),
                                         static_cast<float>(v[3 * node + 2]))
                                  : Vec3::Zero());
        }
        return;
    }
    Level& coarser = levels_[index + 1];
    const uint32_t n = level.size;
    smooth_from_zero_pass(level.inverse, level.rhs, 0, n, level.x);
    multiply(level, level.x, level.product);
    // Restrict the residual: each coarse node sums its aggregate's.
    coarser.rhs.fill(Vec3::Zero());
    const uint32_t* to = level.aggregate.data();
    for (uint32_t node = 0; node < n; ++node) {
        coarser.rhs.x[to[node]] += level.rhs.x[node] - level.product.x[node];
        coarser.rhs.y[to[node]] += level.rhs.y[node] - level.product.y[node];
        coarser.rhs.z[to[node]] += level.rhs.z[node] - level.product.z[node];
    }
    cycle(index + 1);
    for (uint32_t node = 0; node < n; ++node) {
        level.x.x[node] += coarser.x.x[to[node]];
        level.x.y[node] += coarser.x.y[to[node]];
        level.x.z[node] += coarser.x.z[to[node]];
    }
    multiply(level, level.x, level.product);
    smooth_pass(level.inverse, level.rhs, level.product, 0, n, level.x);
}

void Multigrid::restrict_residual(const Vec3Soa& t, const GroupTask& task) {
    Level& top = levels_.front();
    uint32_t begin, end;
    task.items(top.size, begin, end);
    for (uint32_t node = begin; node < end; ++node) {
        float x = 0, y = 0, z = 0;
        for (uint32_t k = child_start_[node]; k < child_start_[node + 1]; ++k) {
            const uint32_t i = child_[k];
            x += t.x[i];
            y += t.y[i];
            z += t.z[i];
        }
        top.rhs.x[node] = x;
        top.rhs.y[node] = y;
        top.rhs.z[node] = z;
    }
}

void Multigrid::correct_coarse() { cycle(0); }

void Multigrid::smooth_from_zero(const LinearSystem& system, const Vec3Soa& r, uint32_t begin, uint32_t end,
                                 Vec3Soa& z) {
    smooth_from_zero_pass(*system.diagonal_inverse, r, begin, end, z);
}

CLOTH_HOT_LOOP void Multigrid::residual(const LinearSystem& system, const Vec3Soa& r, const Vec3Soa& z,
                                        uint32_t begin, uint32_t end, Vec3Soa& t) {
    multiply_system(system, z, begin, end, t);
    for_each_lane_group(begin, end, begin, end, [&](auto lanes, uint32_t i) {
        using L = decltype(lanes);
        store_vec3<L>(t, i, L::load(&r.x[i]) - L::load(&t.x[i]), L::load(&r.y[i]) - L::load(&t.y[i]),
                      L::load(&r.z[i]) - L::load(&t.z[i]));
    });
}

void Multigrid::prolong(const float* pinned, uint32_t begin, uint32_t end, Vec3Soa& z) const {
    const Vec3Soa& e = levels_.front().x;
    for (uint32_t i = begin; i < end; ++i) {
        const uint32_t from = aggregate_[i];
        const float free = 1.0f - pinned[i];
        z.x[i] += e.x[from] * free;
        z.y[i] += e.y[from] * free;
        z.z[i] += e.z[from] * free;
    }
}

}  // namespace cloth
