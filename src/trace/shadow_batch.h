#pragma once
// Shadow rays from one surface point, queued and traced in packets, each
// with the weight it adds when it reaches its end unoccluded. The ground
// truth and env-rays share it (docs/design/TRUTH.md, "Embree scene"). Stack
// storage, so the per-point loops never allocate.
#include <array>
#include <cstdint>
#include <limits>

#include "src/core/math.h"
#include "src/rays/ray_scene.h"

namespace rsl {

class ShadowBatch {
public:
    static constexpr int kCapacity = 64;

    ShadowBatch(const RayScene& rays, const Vec3& origin) : rays_(rays), origin_(origin) {}

    void add(const Vec3& dir, const Color& weight, float t_far = std::numeric_limits<float>::infinity()) {
        dirs_[count_] = dir;
        weights_[count_] = weight;
        t_fars_[count_] = t_far;
        if (++count_ == kCapacity) flush();
    }
    // Sum of the weights of the visible rays so far.
    DVec3 flush_and_sum() {
        flush();
        return sum_;
    }
    uint64_t rays() const { return rays_traced_; }

private:
    void flush() {
        if (count_ == 0) return;
        rays_.occluded_batch(origin_, dirs_.data(), t_fars_.data(), count_, 0.0f, visible_.data());
        for (int k = 0; k < count_; ++k)
            if (visible_[k]) sum_ += DVec3(weights_[k]);
        rays_traced_ += uint64_t(count_);
        count_ = 0;
    }

    const RayScene& rays_;
    Vec3 origin_;
    std::array<Vec3, kCapacity> dirs_;
    std::array<Color, kCapacity> weights_;
    std::array<float, kCapacity> t_fars_;
    std::array<uint8_t, kCapacity> visible_;
    int count_ = 0;
    DVec3 sum_{0.0};
    uint64_t rays_traced_ = 0;
};

}  // namespace rsl
