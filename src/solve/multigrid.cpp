#include "solve/multigrid.h"

#include <algorithm>
#include <cmath>

#include "base/lanes.h"

namespace cloth {
namespace {

constexpr uint32_t kNone = ~0u;

// Pairs (a, b), a < b, as one sortable key.
uint64_t pair_key(uint32_t a, uint32_t b) {
    return a < b ? (uint64_t{a} << 32) | b : (uint64_t{b} << 32) | a;
}

// 2 x 2 blocks of a columns x rows grid; returns the coarse node count.
uint32_t aggregate_grid(uint32_t columns, uint32_t rows, HostVector<uint32_t>& aggregate) {
    const uint32_t coarse_columns = (columns + 1) / 2;
    aggregate.resize(size_t{columns} * rows);
    for (uint32_t r = 0; r < rows; ++r) {
        for (uint32_t c = 0; c < columns; ++c) aggregate[r * columns + c] = (r / 2) * coarse_columns + c / 2;
    }
    return coarse_columns * ((rows + 1) / 2);
}

// Greedy aggregation over a graph given as sorted pair keys: in node order,
// a node whose neighbours are all free starts an aggregate with them; a
// node left over joins its first aggregated neighbour, or stands alone.
uint32_t aggregate_graph(uint32_t size, const HostVector<uint64_t>& pairs, const HostMemory* memory,
                         HostVector<uint32_t>& aggregate) {
    HostVector<uint32_t> start{HostAllocator<uint32_t>(memory)}, neighbour{HostAllocator<uint32_t>(memory)};
    start.assign(size + 1, 0);
    for (uint64_t key : pairs) {
        ++start[(key >> 32) + 1];
        ++start[(key & 0xffffffffu) + 1];
    }
    for (uint32_t i = 0; i < size; ++i) start[i + 1] += start[i];
    neighbour.resize(start[size]);
    HostVector<uint32_t> fill(start.begin(), start.end() - 1, HostAllocator<uint32_t>(memory));
    for (uint64_t key : pairs) {
        const uint32_t a = static_cast<uint32_t>(key >> 32), b = static_cast<uint32_t>(key & 0xffffffffu);
        neighbour[fill[a]++] = b;
        neighbour[fill[b]++] = a;
    }
    aggregate.assign(size, kNone);
    uint32_t count = 0;
    for (uint32_t i = 0; i < size; ++i) {
        bool free = aggregate[i] == kNone;
        for (uint32_t k = start[i]; free && k < start[i + 1]; ++k) free = aggregate[neighbour[k]] == kNone;
        if (!free) continue;
        aggregate[i] = count;
        for (uint32_t k = start[i]; k < start[i + 1]; ++k) aggregate[neighbour[k]] = count;
        ++count;
    }
    for (uint32_t i = 0; i < size; ++i) {
        if (aggregate[i] != kNone) continue;
        for (uint32_t k = start[i]; aggregate[i] == kNone && k < start[i + 1]; ++k) {
            aggregate[i] = aggregate[neighbour[k]];
        }
        if (aggregate[i] == kNone) aggregate[i] = count++;
    }
    return count;
}

// The sorted distinct pairs of `level_size` nodes that the given pairs of
// the finer level map onto, and per finer pair its target (a pair index,
// or pair count + node when both ends fall in one aggregate).
template <class PairOf>
void coarse_pairs(uint32_t finer_pairs, PairOf pair_of, const HostVector<uint32_t>& aggregate,
                  HostVector<uint64_t>& keys, HostVector<uint32_t>& target) {
    keys.clear();
    for (uint32_t p = 0; p < finer_pairs; ++p) {
        const auto [a, b] = pair_of(p);
        const uint32_t to_a = aggregate[a], to_b = aggregate[b];
        if (to_a != to_b) keys.push_back(pair_key(to_a, to_b));
    }
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    target.resize(finer_pairs);
    for (uint32_t p = 0; p < finer_pairs; ++p) {
        const auto [a, b] = pair_of(p);
        const uint32_t to_a = aggregate[a], to_b = aggregate[b];
        target[p] =
            to_a == to_b
                ? static_cast<uint32_t>(keys.size()) + to_a
                : static_cast<uint32_t>(std::lower_bound(keys.begin(), keys.end(), pair_key(to_a, to_b)) -
                                        keys.begin());
    }
}

// Lists by key: for each k < keys, the indices i with key_of[i] == k in
// increasing order, at entries start[k] .. start[k + 1] of `items`.
void counting_lists(const HostVector<uint32_t>& key_of, uint32_t keys, HostVector<uint32_t>& start,
                    HostVector<uint32_t>& items) {
    start.assign(keys + 1, 0);
    for (uint32_t key : key_of) ++start[key + 1];
    for (uint32_t k = 0; k < keys; ++k) start[k + 1] += start[k];
    items.resize(key_of.size());
    HostVector<uint32_t> fill(start.begin(), start.end() - 1, start.get_allocator());
    for (uint32_t i = 0; i < key_of.size(); ++i) items[fill[key_of[i]]++] = i;
}

void set_pairs(const HostVector<uint64_t>& keys, HostVector<uint32_t>& first, HostVector<uint32_t>& second) {
    first.resize(keys.size());
    second.resize(keys.size());
    for (size_t p = 0; p < keys.size(); ++p) {
        first[p] = static_cast<uint32_t>(keys[p] >> 32);
        second[p] = static_cast<uint32_t>(keys[p] & 0xffffffffu);
    }
}

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

// The grid shape of a grid fabric with structural springs: its vertical
// structural family joins p to p + columns (a chain has only the offset 1).
bool grid_shape(const Fabric& fabric, uint32_t& columns, uint32_t& rows) {
    const uint32_t n = fabric.particle_count();
    uint32_t widest = 0;
    bool structural = false;
    for (const SpringFamily& family : fabric.grid_families) {
        if (family.kind != kStructural) continue;
        structural = true;
        widest = std::max(widest, family.offset);
    }
    if (!structural) return false;
    columns = widest > 1 ? widest : n;
    rows = n / columns;
    return columns * rows == n;
}

}  // namespace

Multigrid::Level::Level(const HostMemory* memory)
    : pair_first(HostAllocator<uint32_t>(memory)),
      pair_second(HostAllocator<uint32_t>(memory)),
      pair_block(HostAllocator<Sym3>(memory)),
      row_start(HostAllocator<uint32_t>(memory)),
      row_column(HostAllocator<uint32_t>(memory)),
      row_pair(HostAllocator<uint32_t>(memory)),
      pair_family(HostAllocator<uint8_t>(memory)),
      family_offset(HostAllocator<uint32_t>(memory)),
      family_block(HostAllocator<Sym3Soa>(memory)),
      family_block_pointer(HostAllocator<const Sym3Soa*>(memory)),
      diagonal(HostAllocator<Sym3>(memory)),
      diagonal_blocks(memory),
      inverse(memory),
      rhs(memory),
      x(memory),
      product(memory),
      aggregate(HostAllocator<uint32_t>(memory)),
      pair_target(HostAllocator<uint32_t>(memory)) {}

Multigrid::Multigrid(const HostMemory* memory)
    : memory_(memory),
      aggregate_(HostAllocator<uint32_t>(memory)),
      spring_target_(HostAllocator<uint32_t>(memory)),
      target_start_(HostAllocator<uint32_t>(memory)),
      target_spring_(HostAllocator<uint32_t>(memory)),
      child_start_(HostAllocator<uint32_t>(memory)),
      child_(HostAllocator<uint32_t>(memory)),
      inner_(HostAllocator<Sym3>(memory)),
      levels_(HostAllocator<Level>(memory)),
      coarsest_(HostAllocator<double>(memory)),
      coarsest_vector_(HostAllocator<double>(memory)) {}

void Multigrid::plan(const Fabric& fabric, const SpringTerms& springs) {
    levels_.clear();
    const uint32_t n = fabric.particle_count();
    if (n <= kCoarsestSize) return;

    // The fine springs, in the order add_blocks visits them.
    HostVector<uint32_t> first{HostAllocator<uint32_t>(memory_)}, second{HostAllocator<uint32_t>(memory_)};
    springs.for_each_block([&](uint32_t i, uint32_t j, const Sym3&) {
        first.push_back(i);
        second.push_back(j);
    });

    // The first coarse level.
    uint32_t columns = 0, rows = 0;
    uint32_t size = 0;
    const bool grid = grid_shape(fabric, columns, rows);
    HostVector<uint64_t> keys{HostAllocator<uint64_t>(memory_)};
    if (grid) {
        size = aggregate_grid(columns, rows, aggregate_);
    } else {
        // Neighbours along structural springs (all springs if there are none).
        bool structural = fabric.springs_of_kind[kStructural] > 0;
        for (uint32_t s = 0; s < fabric.spring_count(); ++s) {
            if (structural && fabric.spring_kind[s] != kStructural) continue;
            keys.push_back(pair_key(fabric.spring_first[s], fabric.spring_second[s]));
        }
        std::sort(keys.begin(), keys.end());
        keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
        size = aggregate_graph(n, keys, memory_, aggregate_);
    }
    const auto fine_pair = [&](uint32_t s) { return std::pair<uint32_t, uint32_t>{first[s], second[s]}; };
    coarse_pairs(static_cast<uint32_t>(first.size()), fine_pair, aggregate_, keys, spring_target_);
    levels_.emplace_back(memory_);
    levels_.back().size = size;
    if (grid) {
        levels_.back().columns = (columns + 1) / 2;
        levels_.back().rows = (rows + 1) / 2;
    }
    set_pairs(keys, levels_.back().pair_first, levels_.back().pair_second);

    // Coarser levels down to kCoarsestSize nodes.
    while (levels_.back().size > kCoarsestSize) {
        Level next(memory_);
        Level& finer = levels_.back();
        if (finer.columns > 0) {
            next.size = aggregate_grid(finer.columns, finer.rows, finer.aggregate);
            next.columns = (finer.columns + 1) / 2;
            next.rows = (finer.rows + 1) / 2;
        } else {
            HostVector<uint64_t> finer_keys{HostAllocator<uint64_t>(memory_)};
            for (size_t p = 0; p < finer.pair_first.size(); ++p) {
                finer_keys.push_back(pair_key(finer.pair_first[p], finer.pair_second[p]));
            }
            next.size = aggregate_graph(finer.size, finer_keys, memory_, finer.aggregate);
        }
        if (next.size >= finer.size) {  // nothing couples the nodes: no hierarchy
            levels_.clear();
            return;
        }
        const auto pair_of = [&](uint32_t p) {
            return std::pair<uint32_t, uint32_t>{finer.pair_first[p], finer.pair_second[p]};
        };
        coarse_pairs(static_cast<uint32_t>(finer.pair_first.size()), pair_of, finer.aggregate, keys,
                     finer.pair_target);
        set_pairs(keys, next.pair_first, next.pair_second);
        levels_.push_back(std::move(next));
    }
    for (Level& level : levels_) {
        const uint32_t pairs = static_cast<uint32_t>(level.pair_first.size());
        level.row_start.assign(level.size + 1, 0);
        for (uint32_t p = 0; p < pairs; ++p) {
            ++level.row_start[level.pair_first[p] + 1];
            ++level.row_start[level.pair_second[p] + 1];
        }
        for (uint32_t node = 0; node < level.size; ++node) level.row_start[node + 1] += level.row_start[node];
        level.row_column.resize(2 * size_t{pairs});
        level.row_pair.resize(2 * size_t{pairs});
        HostVector<uint32_t> fill(level.row_start.begin(), level.row_start.end() - 1,
                                  HostAllocator<uint32_t>(memory_));
        for (uint32_t p = 0; p < pairs; ++p) {
            const uint32_t a = level.pair_first[p], b = level.pair_second[p];
            level.row_column[fill[a]] = b;
            level.row_pair[fill[a]++] = p;
            level.row_column[fill[b]] = a;
            level.row_pair[fill[b]++] = p;
        }
        level.pair_block.resize(pairs);
        level.diagonal.resize(level.size);
        level.diagonal_blocks.resize(level.size);
        level.inverse.resize(level.size);
        for (Vec3Soa* v : {&level.rhs, &level.x, &level.product}) v->resize(level.size);
        plan_families(level);
    }
    // The fine springs of each level-0 pair, then of each node (springs
    // inside its aggregate), in for_each_block's order; the particles of
    // each node in index order.
    const uint32_t targets = static_cast<uint32_t>(levels_.front().pair_first.size()) + levels_.front().size;
    counting_lists(spring_target_, targets, target_start_, target_spring_);
    counting_lists(aggregate_, levels_.front().size, child_start_, child_);
    inner_.resize(levels_.front().size);
    const size_t unknowns = 3 * size_t{levels_.back().size};
    coarsest_.assign(unknowns * unknowns, 0.0);
    coarsest_vector_.assign(unknowns, 0.0);
}

// A grid level's pairs as the four families of its 3 x 3 stencil, if every
// pair is one of them (a grid of at least 3 columns, where north-west is
// not east).
void Multigrid::plan_families(Level& level) {
    const uint32_t columns = level.columns;
    if (columns < 3) return;
    const uint32_t pairs = static_cast<uint32_t>(level.pair_first.size());
    level.pair_family.resize(pairs);
    for (uint32_t p = 0; p < pairs; ++p) {
        const uint32_t a = level.pair_first[p], b = level.pair_second[p];  // a < b
        const int dc = static_cast<int>(b % columns) - static_cast<int>(a % columns);
        const uint32_t dr = b / columns - a / columns;
        const int family = dr == 0 && dc == 1    ? 0
                           : dr == 1 && dc == 0  ? 1
                           : dr == 1 && dc == 1  ? 2
                           : dr == 1 && dc == -1 ? 3
                                                 : -1;
        if (family < 0) {
            level.pair_family.clear();
            return;
        }
        level.pair_family[p] = static_cast<uint8_t>(family);
    }
    level.family_offset = {1, columns, columns + 1, columns - 1};
    level.family_pad = columns + 1;
    for (int f = 0; f < 4; ++f)
        level.family_block.emplace_back(memory_).resize(level.family_pad + level.size);
    for (const Sym3Soa& block : level.family_block) level.family_block_pointer.push_back(&block);
}

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
