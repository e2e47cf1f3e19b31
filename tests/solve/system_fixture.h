// One substep's system of a perturbed, stiff grid cloth pinned at its two
// top corners, owned together with its buffers: what the solver tests
// solve.
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "forces/spring_terms.h"
#include "solve/linear_system.h"
#include "solve/solvers.h"
#include "test_support.h"

namespace cloth::testing {

struct SystemFixture {
    SystemFixture(uint32_t columns, uint32_t rows, float stiffness, float h)
        : SystemFixture(make_grid(columns, rows), columns - 1, stiffness, h) {}

    // Any fabric, pinned at particles 0 and second_pin.
    SystemFixture(std::shared_ptr<Fabric> fabric_in, uint32_t second_pin, float stiffness, float h)
        : fabric(std::move(fabric_in)),
          material(uniform_material(stiffness, 0.5f, 1.0f)),
          cloth(heap(), fabric, material, SolverSettings{}, still_air()),
          external(heap()),
          rhs(heap()),
          p(heap()),
          diagonal(heap()),
          inverse(heap()),
          work(heap()) {
        const uint32_t n = fabric->particle_count();
        cloth.pin(0);
        cloth.pin(second_pin);
        perturb(cloth, 0.03f);
        springs = make_spring_terms(heap(), fabric, material);
        springs->evaluate(cloth.positions(), cloth.velocities(), h, SpringModel::make(true), 0,
                          springs->item_count());
        for (Vec3Soa* a : {&external, &rhs, &p}) a->resize(n);
        diagonal.resize(n);
        inverse.resize(n);
        work.resize(n);
        pinned.assign(n, 0.0f);
        pinned[0] = pinned[second_pin] = 1.0f;
        for (uint32_t i = 0; i < n; ++i) external.set(i, Vec3(0, -9.81f, 0) * cloth.masses()[i]);
        assembly = AssemblyPass{springs.get(), &external, cloth.masses().data(), pinned.data(), h, 0.0f};
        assemble_particles(assembly, 0, n, diagonal, inverse, rhs, p);
        system = LinearSystem{springs.get(), n, &diagonal, &inverse, &rhs, pinned.data()};
    }

    // |W dv - b| / |b| over free particles, through the matrix-free product.
    double relative_residual(const Vec3Soa& dv) {
        Vec3Soa product(heap());
        product.resize(system.particle_count);
        multiply_system(system, dv, 0, system.particle_count, product);
        double residual = 0, norm = 0;
        for (uint32_t i = 0; i < system.particle_count; ++i) {
            if (pinned[i] != 0.0f) continue;
            residual += (product.get(i) - rhs.get(i)).squaredNorm();
            norm += rhs.get(i).squaredNorm();
        }
        return std::sqrt(residual / norm);
    }

    // The largest difference of dv from Eigen's CG solution (to 1e-8), over
    // the largest step of that solution.
    double difference_from_cg(const Vec3Soa& dv) {
        Vec3Soa reference(guess());
        solve_cg(system, 1e-8f, 10000, reference);
        double worst = 0, scale = 0;
        for (uint32_t i = 0; i < system.particle_count; ++i) {
            worst = std::max(worst, double((dv.get(i) - reference.get(i)).norm()));
            scale = std::max(scale, double(reference.get(i).norm()));
        }
        return worst / scale;
    }

    Vec3Soa guess() {
        Vec3Soa dv(heap());
        dv.resize(system.particle_count);
        external_force_guess(assembly, 0, system.particle_count, dv);
        return dv;
    }

    std::shared_ptr<Fabric> fabric;
    Material material;
    ClothInstance cloth;
    std::shared_ptr<SpringTerms> springs;
    Vec3Soa external, rhs, p;
    Sym3Soa diagonal, inverse;
    std::vector<float> pinned;
    AssemblyPass assembly{};
    LinearSystem system{};
    SolverWorkspace work;
};

}  // namespace cloth::testing
