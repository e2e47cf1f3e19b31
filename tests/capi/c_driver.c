/*
 * End-to-end drive of the cloth C API from plain C99, through the shared
 * library only (link against cloth_shared and libm; no C++ anywhere here).
 *
 * Exit status 0 on success; otherwise every failed check is printed and the
 * program returns 1.
 */
#include <cloth/cloth.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define COLUMNS 12u
#define ROWS 12u
#define PARTICLES (COLUMNS * ROWS)
#define FRAMES 120
#define DT (1.0f / 60.0f)

static int g_failures = 0;

#define CHECK(cond, ...)                                                         \
    do {                                                                         \
        if (!(cond)) {                                                           \
            ++g_failures;                                                        \
            fprintf(stderr, "c_driver: FAILED %s (line %d): ", #cond, __LINE__); \
            fprintf(stderr, __VA_ARGS__);                                        \
            fprintf(stderr, "\n");                                               \
        }                                                                        \
    } while (0)

/* A call that must succeed. */
#define CHECK_OK(call)                                                                           \
    do {                                                                                         \
        cloth_result check_ok_result_ = (call);                                                  \
        if (check_ok_result_ != CLOTH_OK) {                                                      \
            ++g_failures;                                                                        \
            fprintf(stderr, "c_driver: FAILED %s (line %d): returned %s: %s\n", #call, __LINE__, \
                    cloth_result_name(check_ok_result_), cloth_get_last_error());                \
        }                                                                                        \
    } while (0)

/* ------------------------------------------------------------------ */
/* Host callbacks: a counting, aligning allocator and a log recorder.    */
/* ------------------------------------------------------------------ */

typedef struct host {
    unsigned long allocs;
    unsigned long frees;
    size_t live_bytes;
    size_t peak_bytes;
    unsigned long bad_calls; /* wrong user pointer, bad alignment, size mismatch, NULL free */
    unsigned long log_errors;
    unsigned long log_other;
    cloth_result last_logged_code;
    char last_logged_message[512];
} host;

/* Each block carries a header in front of the aligned pointer. */
typedef struct block_header {
    void* raw;
    size_t size;
    size_t magic;
} block_header;

#define BLOCK_MAGIC ((size_t)0x5ca1ab1eu)

static void* host_alloc(size_t size, size_t alignment, void* user) {
    host* h = (host*)user;
    unsigned char* raw;
    size_t address;
    block_header* header;
    if (alignment == 0 || (alignment & (alignment - 1)) != 0 || alignment > 64) {
        ++h->bad_calls;
        fprintf(stderr, "c_driver: alloc with alignment %lu\n", (unsigned long)alignment);
        return NULL;
    }
    if (alignment < sizeof(void*)) alignment = sizeof(void*);
    raw = (unsigned char*)malloc(size + alignment + sizeof(block_header));
    if (raw == NULL) return NULL;
    address = (size_t)(raw + sizeof(block_header));
    address = (address + alignment - 1) & ~(alignment - 1);
    header = (block_header*)address - 1;
    header->raw = raw;
    header->size = size;
    header->magic = BLOCK_MAGIC;
    ++h->allocs;
    h->live_bytes += size;
    if (h->live_bytes > h->peak_bytes) h->peak_bytes = h->live_bytes;
    return (void*)address;
}

static void host_free(void* ptr, size_t size, void* user) {
    host* h = (host*)user;
    block_header* header;
    if (ptr == NULL) {
        ++h->bad_calls;
        fprintf(stderr, "c_driver: free called with NULL\n");
        return;
    }
    header = (block_header*)ptr - 1;
    if (header->magic != BLOCK_MAGIC) {
        ++h->bad_calls;
        fprintf(stderr, "c_driver: free of a pointer the allocator never returned\n");
        return;
    }
    if (header->size != size) {
        ++h->bad_calls;
        fprintf(stderr, "c_driver: free size %lu, allocated %lu\n", (unsigned long)size,
                (unsigned long)header->size);
    }
    header->magic = 0;
    ++h->frees;
    h->live_bytes -= header->size;
    free(header->raw);
}

static void host_log(cloth_log_level level, cloth_result code, const char* message, void* user) {
    host* h = (host*)user;
    if (message == NULL) {
        ++h->bad_calls;
        return;
    }
    if (level == CLOTH_LOG_ERROR) {
        ++h->log_errors;
        h->last_logged_code = code;
        strncpy(h->last_logged_message, message, sizeof h->last_logged_message - 1);
        h->last_logged_message[sizeof h->last_logged_message - 1] = '\0';
    } else {
        ++h->log_other;
    }
}

/* ------------------------------------------------------------------ */
/* Helpers                                                              */
/* ------------------------------------------------------------------ */

static int all_finite(const float* v, size_t n) {
    size_t i;
    for (i = 0; i < n; ++i) {
        if (!isfinite(v[i])) return 0;
    }
    return 1;
}

static double mean_y_of_free(const float* xyz) {
    double sum = 0.0;
    unsigned i;
    for (i = COLUMNS; i < PARTICLES; ++i) sum += xyz[3 * i + 1]; /* rows 1.. are free */
    return sum / (double)(PARTICLES - COLUMNS);
}

static void check_normals(const char* what, cloth_id cloth) {
    float normals[3 * PARTICLES];
    unsigned i;
    float worst = 0.0f;
    CHECK_OK(cloth_read_normals(cloth, normals, 3 * PARTICLES));
    CHECK(all_finite(normals, 3 * PARTICLES), "%s: normals not finite", what);
    for (i = 0; i < PARTICLES; ++i) {
        const float* n = normals + 3 * i;
        float err = (float)fabs(sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]) - 1.0);
        if (err > worst) worst = err;
    }
    CHECK(worst < 1e-3f, "%s: a normal is not unit length (| |n| - 1 | = %g)", what, (double)worst);
}

static void check_stats(const char* what, cloth_id cloth) {
    cloth_stats stats;
    memset(&stats, 0, sizeof stats);
    stats.struct_size = (uint32_t)sizeof stats;
    CHECK_OK(cloth_get_stats(cloth, &stats));
    CHECK(stats.last_step_result == CLOTH_OK, "%s: last_step_result %s", what,
          cloth_result_name(stats.last_step_result));
    CHECK(isfinite(stats.kinetic_energy) && isfinite(stats.gravity_energy) && isfinite(stats.elastic_energy),
          "%s: non-finite energy", what);
    CHECK(stats.kinetic_energy >= 0.0 && stats.elastic_energy >= 0.0, "%s: negative energy", what);
    CHECK(isfinite(stats.max_speed) && stats.max_speed >= 0.0f, "%s: max_speed %g", what,
          (double)stats.max_speed);
}

/* ------------------------------------------------------------------ */

int main(void) {
    host h;
    cloth_version version = cloth_get_version();
    cloth_world_desc world_desc;
    cloth_world_id world = {0, 0};
    cloth_grid_desc grid;
    cloth_fabric_id fabric = {0, 0, 0, 0};
    cloth_desc desc;
    cloth_id jacobi = {0, 0, 0, 0};
    cloth_id cg = {0, 0, 0, 0};
    cloth_solver_settings settings;
    uint32_t count = 0;
    uint32_t top_row[COLUMNS];
    float pin_start[3 * COLUMNS];
    float pin_target[3 * COLUMNS];
    static float start[3 * PARTICLES];
    static float positions[3 * PARTICLES];
    static float velocities[3 * PARTICLES];
    const float wind[3] = {0.5f, 0.0f, 0.5f};
    bool pinned = false;
    int frame;
    unsigned i;

    memset(&h, 0, sizeof h);

    /* Version: the loaded library must be the one this header describes. */
    CHECK(version.major == CLOTH_VERSION_MAJOR && version.minor == CLOTH_VERSION_MINOR,
          "library version %u.%u.%u, header %d.%d.%d", (unsigned)version.major, (unsigned)version.minor,
          (unsigned)version.patch, CLOTH_VERSION_MAJOR, CLOTH_VERSION_MINOR, CLOTH_VERSION_PATCH);
    CHECK(strcmp(cloth_result_name(CLOTH_OK), "CLOTH_OK") == 0, "cloth_result_name(CLOTH_OK) is \"%s\"",
          cloth_result_name(CLOTH_OK));

    /* World with host callbacks. */
    world_desc = cloth_default_world_desc();
    world_desc.alloc = host_alloc;
    world_desc.free = host_free;
    world_desc.log = host_log;
    world_desc.user = &h;
    CHECK_OK(cloth_world_create(&world_desc, &world));

    /* A horizontal 12x12 grid, 1 m x 1 m, at y = 1; row 0 is the edge that gets pinned. */
    grid = cloth_default_grid_desc();
    grid.columns = COLUMNS;
    grid.rows = ROWS;
    grid.origin[0] = 0.0f;
    grid.origin[1] = 1.0f;
    grid.origin[2] = 0.0f;
    grid.u[0] = 1.0f;
    grid.u[1] = 0.0f;
    grid.u[2] = 0.0f;
    grid.v[0] = 0.0f;
    grid.v[1] = 0.0f;
    grid.v[2] = 1.0f;
    CHECK_OK(cloth_fabric_create_grid(world, &grid, &fabric));
    CHECK_OK(cloth_fabric_get_particle_count(fabric, &count));
    CHECK(count == PARTICLES, "fabric has %u particles, expected %u", (unsigned)count, PARTICLES);

    /* Two cloths sharing the fabric: one Jacobi, one conjugate gradient. */
    desc = cloth_default_desc();
    desc.fabric = fabric;
    desc.solver.kind = CLOTH_SOLVER_JACOBI;
    desc.solver.iterations = 4;
    CHECK_OK(cloth_create(world, &desc, &jacobi));
    desc = cloth_default_desc();
    desc.fabric = fabric;
    desc.solver.kind = CLOTH_SOLVER_CG;
    CHECK_OK(cloth_create(world, &desc, &cg));
    CHECK(cloth_is_valid(jacobi) && cloth_is_valid(cg) && !cloth_id_equal(jacobi, cg),
          "two live cloths are not valid and distinct");
    CHECK_OK(cloth_get_particle_count(cg, &count));
    CHECK(count == PARTICLES, "cloth has %u particles, expected %u", (unsigned)count, PARTICLES);
    CHECK_OK(cloth_read_positions(jacobi, start, 3 * PARTICLES));

    /* Pin the top row of both. */
    for (i = 0; i < COLUMNS; ++i) top_row[i] = i;
    CHECK_OK(cloth_pin(jacobi, top_row, COLUMNS));
    CHECK_OK(cloth_pin(cg, top_row, COLUMNS));
    CHECK_OK(cloth_is_pinned(jacobi, 0, &pinned));
    CHECK(pinned, "particle 0 is not pinned after cloth_pin");
    CHECK_OK(cloth_is_pinned(jacobi, COLUMNS, &pinned));
    CHECK(!pinned, "particle %u is pinned but was never pinned", COLUMNS);
    memcpy(pin_start, start, sizeof pin_start);

    CHECK_OK(cloth_set_wind(jacobi, wind));
    CHECK_OK(cloth_set_wind(cg, wind));

    /* 120 frames; the pinned edge slides 0.2 m along x over the first 60. */
    for (frame = 0; frame < FRAMES; ++frame) {
        if (frame < 60) {
            float shift = 0.2f * (float)(frame + 1) / 60.0f;
            for (i = 0; i < COLUMNS; ++i) {
                pin_target[3 * i + 0] = pin_start[3 * i + 0] + shift;
                pin_target[3 * i + 1] = pin_start[3 * i + 1];
                pin_target[3 * i + 2] = pin_start[3 * i + 2];
            }
            CHECK_OK(cloth_set_pin_targets(jacobi, top_row, pin_target, COLUMNS));
            CHECK_OK(cloth_set_pin_targets(cg, top_row, pin_target, COLUMNS));
        }
        CHECK_OK(cloth_step(world, DT));
        if (g_failures > 20) break;
    }

    {
        cloth_id both[2];
        const char* names[2] = {"jacobi", "cg"};
        int c;
        both[0] = jacobi;
        both[1] = cg;
        for (c = 0; c < 2; ++c) {
            double dy;
            float worst_pin = 0.0f;
            CHECK_OK(cloth_read_positions(both[c], positions, 3 * PARTICLES));
            CHECK_OK(cloth_read_velocities(both[c], velocities, 3 * PARTICLES));
            CHECK(all_finite(positions, 3 * PARTICLES), "%s: positions not finite", names[c]);
            CHECK(all_finite(velocities, 3 * PARTICLES), "%s: velocities not finite", names[c]);
            dy = mean_y_of_free(positions) - mean_y_of_free(start);
            /* CG must fall; 4 Jacobi sweeps at this stiffness-to-mass ratio are the
               unstable regime of docs/method.md, "Where one iteration stops holding", so only boundedness is
               asked. */
            if (c == 1) {
                CHECK(dy < -0.05, "%s: the free particles did not fall (mean y moved by %g m)", names[c], dy);
            } else {
                CHECK(fabs(dy) < 2.0, "%s: the free particles left a 2 m band (mean y moved by %g m)",
                      names[c], dy);
            }
            for (i = 0; i < COLUMNS; ++i) {
                float e = (float)fabs((double)positions[3 * i] - (double)pin_target[3 * i]);
                e += (float)fabs((double)positions[3 * i + 1] - (double)pin_target[3 * i + 1]);
                e += (float)fabs((double)positions[3 * i + 2] - (double)pin_target[3 * i + 2]);
                if (e > worst_pin) worst_pin = e;
            }
            CHECK(worst_pin < 1e-5f, "%s: a pinned particle is %g m from its target", names[c],
                  (double)worst_pin);
            check_normals(names[c], both[c]);
            check_stats(names[c], both[c]);
        }
    }

    /* Change solver and stiffness at run time. */
    settings = cloth_default_solver_settings();
    settings.kind = CLOTH_SOLVER_CG;
    settings.cg_tolerance = 1e-5f;
    CHECK_OK(cloth_set_solver(jacobi, &settings));
    memset(&settings, 0, sizeof settings);
    settings.struct_size = (uint32_t)sizeof settings;
    CHECK_OK(cloth_get_solver(jacobi, &settings));
    CHECK(settings.kind == CLOTH_SOLVER_CG && settings.cg_tolerance == 1e-5f,
          "cloth_get_solver does not report the settings just set (kind %d)", (int)settings.kind);
    settings = cloth_default_solver_settings();
    settings.kind = CLOTH_SOLVER_JACOBI;
    settings.substeps = 4;
    CHECK_OK(cloth_set_solver(cg, &settings));
    {
        cloth_spring_params stiff;
        stiff.stiffness = 5000.0f;
        stiff.damping = 1.0f;
        CHECK_OK(cloth_set_spring_params(jacobi, CLOTH_SPRING_STRUCTURAL, stiff));
        CHECK_OK(cloth_set_spring_params(cg, CLOTH_SPRING_STRUCTURAL | CLOTH_SPRING_SHEAR, stiff));
    }
    for (frame = 0; frame < 30; ++frame) CHECK_OK(cloth_step(world, DT));
    CHECK_OK(cloth_read_positions(jacobi, positions, 3 * PARTICLES));
    CHECK(all_finite(positions, 3 * PARTICLES), "jacobi->cg: positions not finite");
    CHECK_OK(cloth_read_positions(cg, positions, 3 * PARTICLES));
    CHECK(all_finite(positions, 3 * PARTICLES), "cg->jacobi: positions not finite");
    check_normals("after solver change", jacobi);
    check_stats("after solver change", cg);

    /* No errors so far; a deliberate one reaches the log callback. */
    CHECK(h.log_errors == 0, "%lu errors were logged during a valid run; last: %s: %s", h.log_errors,
          cloth_result_name(h.last_logged_code), h.last_logged_message);
    {
        const float bad_wind[3] = {0.0f, INFINITY, 0.0f};
        cloth_result r = cloth_set_wind(cg, bad_wind);
        CHECK(r == CLOTH_ERROR_NOT_FINITE, "cloth_set_wind(inf) returned %s", cloth_result_name(r));
        CHECK(cloth_get_last_error()[0] != '\0', "no last-error message after a failed call");
        CHECK(h.log_errors == 1 && h.last_logged_code == CLOTH_ERROR_NOT_FINITE,
              "log callback got %lu errors, last code %s", h.log_errors,
              cloth_result_name(h.last_logged_code));
        CHECK(strcmp(h.last_logged_message, cloth_get_last_error()) == 0,
              "logged message \"%s\" differs from cloth_get_last_error() \"%s\"", h.last_logged_message,
              cloth_get_last_error());
    }

    /* Tear down. */
    CHECK_OK(cloth_destroy(jacobi));
    CHECK(cloth_read_positions(jacobi, positions, 3 * PARTICLES) == CLOTH_ERROR_INVALID_HANDLE,
          "a destroyed cloth is still readable");
    CHECK(!cloth_is_valid(jacobi) && !cloth_is_valid(cloth_null_id), "a destroyed or null cloth is valid");
    CHECK_OK(cloth_fabric_destroy(fabric));
    CHECK_OK(cloth_step(world, DT)); /* the CG cloth outlives its fabric handle */
    CHECK_OK(cloth_destroy(cg));
    CHECK_OK(cloth_world_destroy(world));
    CHECK(cloth_step(world, DT) == CLOTH_ERROR_INVALID_HANDLE, "a destroyed world still steps");
    CHECK(!cloth_world_is_valid(world) && !cloth_world_id_equal(world, cloth_null_world_id),
          "a destroyed world id is valid, or null");

    CHECK(h.allocs > 0, "the world never used the host allocator");
    CHECK(h.allocs == h.frees, "%lu allocations, %lu frees", h.allocs, h.frees);
    CHECK(h.live_bytes == 0, "%lu bytes still allocated after cloth_world_destroy",
          (unsigned long)h.live_bytes);
    CHECK(h.bad_calls == 0, "%lu invalid allocator/log calls", h.bad_calls);

    if (g_failures != 0) {
        fprintf(stderr, "c_driver: %d check(s) failed\n", g_failures);
        return 1;
    }
    printf("c_driver: ok (%lu allocations, peak %lu bytes)\n", h.allocs, (unsigned long)h.peak_bytes);
    return 0;
}
