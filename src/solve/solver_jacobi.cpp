// Jacobi sweeps on W dv = b. Each sweep is one per-particle loop that reads
// the previous iterate only, so particles are independent within a sweep
// (the barrier is between sweeps); the sums run in the fabric's fixed
// incidence order, so the result does not depend on who runs which range.
#include <utility>

#include "solve/solvers.h"

namespace cloth {

SolveReport solve_jacobi(const LinearSystem& system, uint32_t iterations, Vec3Soa& dv, Vec3Soa& scratch) {
    Vec3Soa* current = &dv;
    Vec3Soa* next = &scratch;
    for (uint32_t k = 0; k < iterations; ++k) {
        jacobi_sweep(system, *current, 0, system.particle_count, *next);
        std::swap(current, next);
    }
    if (current != &dv) std::swap(dv, *current);
    SolveReport report;
    report.iterations = iterations;
    return report;
}

}  // namespace cloth
