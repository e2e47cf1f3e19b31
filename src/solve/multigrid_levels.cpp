// Multigrid's levels (multigrid.h), built once per cloth: the aggregates of
// each level, its coupled pairs, and the maps from the fine springs and
// particles onto the first level that the per-substep assembly gathers.
#include <algorithm>

#include "fabric/grid_coarsening.h"
#include "solve/multigrid.h"

namespace cloth {
namespace {

constexpr uint32_t kNone = ~0u;

// Pairs (a, b), a < b, as one sortable key.
uint64_t pair_key(uint32_t a, uint32_t b) {
    return a < b ? (uint64_t{a} << 32) | b : (uint64_t{b} << 32) | a;
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
        levels_.back().columns = coarse_grid_extent(columns);
        levels_.back().rows = coarse_grid_extent(rows);
    }
    set_pairs(keys, levels_.back().pair_first, levels_.back().pair_second);

    // Coarser levels down to kCoarsestSize nodes.
    while (levels_.back().size > kCoarsestSize) {
        Level next(memory_);
        Level& finer = levels_.back();
        if (finer.columns > 0) {
            next.size = aggregate_grid(finer.columns, finer.rows, finer.aggregate);
            next.columns = coarse_grid_extent(finer.columns);
            next.rows = coarse_grid_extent(finer.rows);
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

}  // namespace cloth
