#include "field.h"

#include <algorithm>
#include <cmath>

namespace flag_field {

const char* class_name(FlagClass c) {
    switch (c) {
        case kNear:
            return "near";
        case kMid:
            return "mid";
        default:
            return "far";
    }
}

namespace {

// Flag k's distance from the course line: 2 m growing by 16.5 % a flag
// (about 200 m for the 31st).
float distance_of(uint32_t k) { return 2.0f * std::pow(1.165f, static_cast<float>(k)); }

FlagClass class_of(float distance) { return distance < 10.0f ? kNear : distance < 50.0f ? kMid : kFar; }

}  // namespace

bool FlagField::create(cloth_world_id world, const double origin[3], const vehicle_flag::Terrain& terrain,
                       uint32_t count, uint32_t max_update_rate, std::string* error) {
    auto failed = [&](const char* call) {
        *error = std::string(call) + ": " + cloth_get_last_error();
        return false;
    };
    for (uint32_t k = 0; k < count; ++k) {
        FieldFlag f;
        f.distance = distance_of(k);
        f.flag_class = class_of(f.distance);
        const float side = k % 2 == 0 ? 1.0f : -1.0f;  // both sides of the course
        const float x = side * f.distance, z = 10.0f + 11.0f * static_cast<float>(k);
        f.pole[0] = x;
        f.pole[1] = terrain.height_at(x, z);
        f.pole[2] = z;
        float local[3];
        for (int a = 0; a < 3; ++a) local[a] = static_cast<float>(f.pole[a] - origin[a]);

        cloth_collider_desc pole = cloth_default_collider_desc();
        pole.local_position[0] = local[0];
        pole.local_position[1] = local[1] + 0.5f * kPoleHeight;
        pole.local_position[2] = local[2];
        cloth_collider_id collider{};
        if (cloth_collider_create_capsule(world, &pole, kPoleRadius, 0.5f * kPoleHeight, &collider) !=
            CLOTH_OK)
            return failed("cloth_collider_create_capsule");

        // The flag hangs from the pole's top, out along +x (downwind).
        cloth_grid_desc grid = cloth_default_grid_desc();
        grid.columns = kColumns;
        grid.rows = kRows;
        grid.origin[0] = local[0] + 2.0f * kPoleRadius;
        grid.origin[1] = local[1] + kPoleHeight;
        grid.origin[2] = local[2];
        grid.u[0] = 1.2f;
        grid.v[1] = -0.8f;
        cloth_fabric_id fabric{};
        if (cloth_fabric_create_grid(world, &grid, &fabric) != CLOTH_OK)
            return failed("cloth_fabric_create_grid");
        cloth_desc desc = cloth_default_desc();
        desc.fabric = fabric;
        desc.area_density = 0.25f;
        desc.structural.stiffness = 1000.0f;
        desc.shear.stiffness = 200.0f;
        desc.bend.stiffness = 20.0f;
        if (cloth_create(world, &desc, &f.cloth) != CLOTH_OK) return failed("cloth_create");
        if (triangles_.empty()) {
            uint32_t triangle_count = 0;
            cloth_fabric_get_triangle_count(fabric, &triangle_count);
            triangles_.resize(3 * triangle_count);
            cloth_fabric_read_triangles(fabric, triangles_.data(), 3 * triangle_count);
        }
        cloth_fabric_destroy(fabric);  // the cloth keeps it
        std::vector<uint32_t> column;
        for (uint32_t r = 0; r < kRows; ++r) column.push_back(r * kColumns);
        if (cloth_pin(f.cloth, column.data(), kRows) != CLOTH_OK) return failed("cloth_pin");
        cloth_sleep_params sleep = cloth_default_sleep_params();
        sleep.enabled = 0;  // gusts never let it rest
        cloth_quality_policy policy = cloth_default_quality_policy();
        policy.enabled = 1;
        policy.max_update_rate = max_update_rate;
        // Room for the default's own substeps (16 at most): a flag going to
        // rate 8 while it flaps takes up to 8 in its first slow step, where
        // the policy's default of 4 would cut it short.
        policy.max_substeps = 16;
        if (cloth_set_sleep(f.cloth, &sleep) != CLOTH_OK) return failed("cloth_set_sleep");
        if (cloth_set_quality_policy(f.cloth, &policy) != CLOTH_OK) return failed("cloth_set_quality_policy");
        flags_.push_back(std::move(f));
    }
    return true;
}

void FlagField::set_wind(float time) {
    for (size_t k = 0; k < flags_.size(); ++k) {
        const float phase = 0.7f * static_cast<float>(k);
        const float wind[3] = {8.0f + 2.0f * std::sin(0.9f * time + phase), 0.0f,
                               1.0f + 1.5f * std::sin(1.9f * time + 2.0f * phase)};
        cloth_set_wind(flags_[k].cloth, wind);
    }
}

void FlagField::observe(uint64_t frame, const double origin[3], float max_strain, float tolerance,
                        FieldChecks* checks) {
    const uint32_t n = kColumns * kRows;
    std::vector<float> x(3 * n);
    for (FieldFlag& f : flags_) {
        cloth_stats stats{};
        stats.struct_size = sizeof stats;
        cloth_get_stats(f.cloth, &stats);
        checks->worst_strain = std::max(checks->worst_strain, stats.max_strain);
        checks->strain_frames += !(stats.max_strain <= max_strain);

        uint32_t rate = 1, phase = 0;
        cloth_get_update_rate(f.cloth, &rate, &phase);
        if (rate != f.rate) f.rate_changes.push_back(static_cast<int>(f.moves.size()));
        f.rate = rate;
        cloth_read_positions(f.cloth, x.data(), 3 * n);
        for (uint32_t i = 0; i < 3 * n; ++i) x[i] = static_cast<float>(double{x[i]} + origin[i % 3]);
        float move = 0;
        if (!f.last.empty()) {
            for (uint32_t i = 0; i < n; ++i) {
                const float dx = x[3 * i] - f.last[3 * i], dy = x[3 * i + 1] - f.last[3 * i + 1],
                            dz = x[3 * i + 2] - f.last[3 * i + 2];
                move = std::max(move, std::sqrt(dx * dx + dy * dy + dz * dz));
            }
        }
        f.moves.push_back(move);
        f.last = x;

        // The pole, where the reported positions are the state.
        if (frame % rate != phase) continue;
        const float radius = kPoleRadius - tolerance;
        for (uint32_t i = 0; i < n; ++i) {
            const float dx = x[3 * i] - static_cast<float>(f.pole[0]),
                        dz = x[3 * i + 2] - static_cast<float>(f.pole[2]);
            const float depth = radius - std::sqrt(dx * dx + dz * dz);
            if (depth > 0.0f) {
                ++checks->inside_pole;
                checks->deepest_in_pole = std::max(checks->deepest_in_pole, depth + tolerance);
            }
        }
    }
}

void FlagField::check_jumps(FieldChecks* checks) const {
    for (const FieldFlag& f : flags_) {
        for (int at : f.rate_changes) {
            if (at < 3 || at + 2 >= static_cast<int>(f.moves.size())) continue;
            float around = 0;
            for (int k : {at - 2, at - 1, at + 1, at + 2}) around = std::max(around, f.moves[k]);
            ++checks->rate_changes;
            const float ratio = around > 0 ? f.moves[at] / around : 0.0f;
            checks->worst_jump_ratio = std::max(checks->worst_jump_ratio, ratio);
            checks->jumps += ratio > 2.0f;
        }
    }
}

}  // namespace flag_field
