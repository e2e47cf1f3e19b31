// Jacobi sweeps on W dv = b. Each sweep is one per-particle loop that reads
// the previous iterate only, so particles are independent within a sweep
// (the barrier is between sweeps); the sums run in the fabric's fixed
// incidence order, so the result does not depend on who runs which range.
#include "solvers.h"

#include <utility>

namespace cloth {

SolveReport solve_jacobi(const LinearSystem& system, uint32_t iterations, Vec3* dv, Vec3* scratch) {
    const uint32_t n = system.particle_count;
    Vec3* current = dv;
    Vec3* next = scratch;
    for (uint32_t k = 0; k < iterations; ++k) {
        gather_neighbours(system, current, 0, n, next);
        for (uint32_t i = 0; i < n; ++i) {
            next[i] = system.diagonal_inverse[i] * (system.rhs[i] + next[i]);
        }
        std::swap(current, next);
    }
    if (current != dv) {
        for (uint32_t i = 0; i < n; ++i) dv[i] = current[i];
    }
    SolveReport report;
    report.iterations = iterations;
    return report;
}

}  // namespace cloth
