// The two spring layouts are the same physics: a grid cloth stepped with
// the grid families matches the same cloth stepped through index pairs,
// and splitting particle ranges does not change a bit.
#include "forces/spring_terms.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>

#include "forces/aerodynamics.h"
#include "solve/linear_system.h"
#include "test_support.h"

namespace cloth {
namespace {

// Evaluates the springs of a perturbed 9x7 grid and gathers per particle.
struct Gathered {
    Vec3Soa force{cloth::testing::heap()};
    Sym3Soa diagonal{cloth::testing::heap()};
    Vec3Soa products{cloth::testing::heap()};
};

Gathered gather_with(const std::shared_ptr<SpringTerms>& terms, const Vec3Soa& x, const Vec3Soa& v,
                     uint32_t split) {
    const uint32_t n = static_cast<uint32_t>(x.size());
    Gathered out;
    out.force.resize(n);
    out.diagonal.resize(n);
    out.products.resize(n);
    terms->evaluate(x, v, 1.0f / 60.0f, SpringModel::make(true), 0, terms->item_count());
    // Two ranges [0, split) and [split, n), as two workers would run them.
    for (auto [begin, end] : {std::pair<uint32_t, uint32_t>{0, split}, {split, n}}) {
        terms->gather(begin, end, out.force, &out.diagonal);
        terms->neighbour_sums(v, begin, end, out.products);
    }
    return out;
}

TEST(SpringTerms, GridFamiliesAndIndexPairsGiveTheSameForcesBlocksAndProducts) {
    auto fabric = cloth::testing::make_grid(9, 7);
    const Material material = cloth::testing::uniform_material(500.0f, 0.3f, 1.0f);
    ClothInstance cloth(cloth::testing::heap(), fabric, material, SolverSettings{},
                        cloth::testing::still_air());
    cloth::testing::perturb(cloth, 0.03f);
    Vec3Soa v(cloth::testing::heap());
    v.resize(cloth.particle_count());
    for (uint32_t i = 0; i < cloth.particle_count(); ++i) v.set(i, Vec3(0.1f * i, -0.05f * i, 0.02f));

    const auto grid = make_spring_terms(cloth::testing::heap(), fabric, material);
    const auto indexed = make_indexed_springs(cloth::testing::heap(), fabric, material);
    const Gathered a = gather_with(grid, cloth.positions(), v, 20);
    const Gathered b = gather_with(indexed, cloth.positions(), v, 41);
    for (uint32_t i = 0; i < cloth.particle_count(); ++i) {
        SCOPED_TRACE(i);
        EXPECT_LT((a.force.get(i) - b.force.get(i)).norm(), 1e-5f * (1 + b.force.get(i).norm()));
        EXPECT_LT((a.diagonal.get(i).to_matrix() - b.diagonal.get(i).to_matrix()).norm(), 1e-6f);
        EXPECT_LT((a.products.get(i) - b.products.get(i)).norm(), 1e-6f * (1 + b.products.get(i).norm()));
    }
    int blocks_a = 0, blocks_b = 0;
    grid->for_each_block([&](uint32_t, uint32_t, const Sym3&) { ++blocks_a; });
    indexed->for_each_block([&](uint32_t, uint32_t, const Sym3&) { ++blocks_b; });
    EXPECT_EQ(blocks_a, blocks_b);
    EXPECT_EQ(static_cast<uint32_t>(blocks_a), fabric->spring_count());
}

TEST(SpringTerms, SplittingTheParticleRangeChangesNoBit) {
    auto fabric = cloth::testing::make_grid(11, 8);
    const Material material = cloth::testing::uniform_material(800.0f, 0.2f, 1.0f);
    ClothInstance cloth(cloth::testing::heap(), fabric, material, SolverSettings{},
                        cloth::testing::still_air());
    cloth::testing::perturb(cloth, 0.05f);
    for (auto make : {make_spring_terms, make_indexed_springs}) {
        const auto terms = make(cloth::testing::heap(), fabric, material);
        const Gathered whole = gather_with(terms, cloth.positions(), cloth.positions(), 88);
        for (uint32_t split : {1u, 13u, 44u, 87u}) {
            const Gathered parts = gather_with(terms, cloth.positions(), cloth.positions(), split);
            for (uint32_t i = 0; i < cloth.particle_count(); ++i) {
                ASSERT_EQ(whole.force.get(i), parts.force.get(i)) << "split " << split << ", particle " << i;
                ASSERT_EQ(whole.diagonal.get(i).to_matrix(), parts.diagonal.get(i).to_matrix());
                ASSERT_EQ(whole.products.get(i), parts.products.get(i));
            }
        }
    }
}

// Assembly, a Jacobi sweep and the air passes over split particle ranges
// give the same bits as over the whole range.
TEST(SpringTerms, AssemblySweepAndAirChangeNoBitWhenTheRangeIsSplit) {
    for (auto fabric : {cloth::testing::make_grid(23, 17), cloth::testing::make_mesh_from_grid(23, 17)}) {
        SCOPED_TRACE(fabric->grid_families.empty() ? "mesh" : "grid");
        const uint32_t n = fabric->particle_count();
        const Material material = cloth::testing::uniform_material(900.0f, 0.4f, 1.0f);
        ClothInstance cloth(cloth::testing::heap(), fabric, material, SolverSettings{},
                            cloth::testing::still_air());
        cloth.pin(0);
        cloth::testing::perturb(cloth, 0.04f);
        std::vector<float> pinned(n, 0.0f);
        pinned[0] = 1.0f;
        AeroParams air;
        air.wind = Vec3(9, 1, 4);
        const auto springs = make_spring_terms(cloth::testing::heap(), fabric, material);
        springs->evaluate(cloth.positions(), cloth.positions(), 1.0f / 60.0f, SpringModel::make(true), 0,
                          springs->item_count());

        struct Outputs {
            Vec3Soa corner{cloth::testing::heap()}, external{cloth::testing::heap()},
                rhs{cloth::testing::heap()}, p{cloth::testing::heap()}, next{cloth::testing::heap()};
            Sym3Soa diagonal{cloth::testing::heap()}, inverse{cloth::testing::heap()};
        };
        auto run = [&](std::vector<uint32_t> cuts) {
            Outputs o;
            o.corner.resize(air_storage_size(*fabric));
            for (Vec3Soa* a : {&o.external, &o.rhs, &o.p, &o.next}) a->resize(n);
            o.diagonal.resize(n);
            o.inverse.resize(n);
            cuts.insert(cuts.begin(), 0);
            cuts.push_back(n);
            const uint32_t items = air_item_count(*fabric);
            evaluate_air(*fabric, air, cloth.positions(), cloth.positions(), 0, items / 3, o.corner);
            evaluate_air(*fabric, air, cloth.positions(), cloth.positions(), items / 3, items, o.corner);
            for (size_t r = 0; r + 1 < cuts.size(); ++r)
                gather_air(*fabric, o.corner, cuts[r], cuts[r + 1], o.external);
            const AssemblyPass pass{springs.get(), &o.external,  cloth.masses().data(),
                                    pinned.data(), 1.0f / 60.0f, 0.1f};
            for (size_t r = 0; r + 1 < cuts.size(); ++r) {
                assemble_particles(pass, cuts[r], cuts[r + 1], o.diagonal, o.inverse, o.rhs, o.p);
            }
            const LinearSystem system{springs.get(), n, &o.diagonal, &o.inverse, &o.rhs, pinned.data()};
            for (size_t r = 0; r + 1 < cuts.size(); ++r)
                jacobi_sweep(system, o.p, cuts[r], cuts[r + 1], o.next);
            return o;
        };
        const Outputs whole = run({});
        const Outputs parts = run({7, 100, 101, 250, n - 3});
        for (uint32_t i = 0; i < n; ++i) {
            ASSERT_EQ(whole.external.get(i), parts.external.get(i)) << "particle " << i;
            ASSERT_EQ(whole.inverse.get(i).to_matrix(), parts.inverse.get(i).to_matrix()) << "particle " << i;
            ASSERT_EQ(whole.rhs.get(i), parts.rhs.get(i)) << "particle " << i;
            ASSERT_EQ(whole.p.get(i), parts.p.get(i)) << "particle " << i;
            ASSERT_EQ(whole.next.get(i), parts.next.get(i)) << "particle " << i;
        }
    }
}

// A grid cloth at rest carries no spring force: every grid spring's rest
// length is the distance between its two particles as the float rest
// positions hold them. (One rest length per family, from u / (columns - 1),
// left springs of a 128 x 128 grid up to 7e-6 m off rest: 0.07 N each at
// 1e4 N/m, a transverse stiffness no one asked for.)
TEST(SpringTerms, AGridAtRestCarriesNoSpringForce) {
    auto fabric = std::make_shared<Fabric>(cloth::testing::heap());
    cloth_grid_desc desc = cloth_default_grid_desc();
    desc.columns = desc.rows = 128;
    desc.origin[1] = 1.5f;
    desc.v[1] = 0.0f;  // horizontal, as the falling-flat scene builds it
    desc.v[2] = 1.0f;
    ASSERT_TRUE(build_grid_fabric(desc, *fabric).ok());
    const float k = 1e4f;
    const Material material = cloth::testing::uniform_material(k, 0.0f, 1.0f);
    const uint32_t n = fabric->particle_count();
    Vec3Soa x(cloth::testing::heap()), v(cloth::testing::heap()), force(cloth::testing::heap());
    for (Vec3Soa* a : {&x, &v, &force}) a->resize(n);
    for (uint32_t i = 0; i < n; ++i) x.set(i, fabric->rest_positions[i]);
    v.fill(Vec3::Zero());
    force.fill(Vec3::Zero());
    const auto grid = make_spring_terms(cloth::testing::heap(), fabric, material);
    grid->evaluate(x, v, 0.0f, SpringModel::make(true), 0, grid->item_count());
    grid->gather(0, n, force, nullptr);
    // A few float roundings of a 7.9 mm length per spring, twelve springs.
    const float rest = 1.0f / 127.0f, allowed = 12 * k * 4 * FLT_EPSILON * rest;
    float largest = 0;
    for (uint32_t i = 0; i < n; ++i) largest = std::max(largest, force.get(i).norm());
    EXPECT_LE(largest, allowed) << "largest spring force on a particle at rest, N";
}

}  // namespace
}  // namespace cloth
