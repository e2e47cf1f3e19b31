#include "scene/frame_budget.h"

namespace cloth {

FrameBudget::FrameBudget(const HostMemory* memory, uint32_t max_cloths)
    : cloths_(HostAllocator<BudgetCloth>(memory)) {
    cloths_.reserve(max_cloths);
}

void FrameBudget::set_viewer(const Vec3* position) {
    has_viewer_ = position != nullptr;
    viewer_ = position ? *position : Vec3::Zero();
}

float FrameBudget::relevance(const SceneCloth& scene) const {
    if (!has_viewer_) return scene.importance();
    const Vec3Soa& x = scene.cloth().positions();
    Vec3 low = x.get(0), high = low;
    for (uint32_t i = 1; i < scene.cloth().particle_count(); ++i) {
        low = low.cwiseMin(x.get(i));
        high = high.cwiseMax(x.get(i));
    }
    const float radius = 0.5f * (high - low).norm();
    const float distance = (0.5f * (low + high) - viewer_).norm();
    return scene.importance() * (distance > radius ? radius / distance : 1.0f);
}

bool FrameBudget::count_frame(double step_ms) {
    const bool over = step_ms > ms_;
    if (over) ++overrun_frames_;
    return over;
}

void FrameBudget::decide(double step_ms, uint64_t frame) {
    policy_.after_frame(ms_, step_ms, frame, cloths_.data(), static_cast<uint32_t>(cloths_.size()));
}

}  // namespace cloth
