#pragma once
// MERL measured isotropic BRDFs (Matusik et al. 2003), the standard binary
// format: three int32 dimensions (90, 90, 180), then 3 × 90·90·180 doubles,
// channel-major (all red, then green, then blue), each scaled by 1/1500,
// 1.15/1500, 1.66/1500. Indexing is by the Rusinkiewicz half/difference angles:
// θ_h with the non-linear index √(θ_h / (π/2)) · 90, θ_d linear over [0, π/2],
// φ_d over [0, π) (φ_d and φ_d + π are the same sample by reciprocity).
//
// The evaluator interpolates trilinearly between bin centers (the reference
// reader takes the nearest bin), so tables built from it are continuous;
// negative bins (unmeasured) read as 0.
#include <filesystem>
#include <memory>
#include <vector>

#include "src/brdf/brdf.h"

namespace rsl {

class MerlBrdf final : public Brdf {
public:
    static constexpr int kThetaH = 90, kThetaD = 90, kPhiD = 180;
    static constexpr int kSamples = kThetaH * kThetaD * kPhiD;
    static constexpr double kScale[3] = {1.0 / 1500.0, 1.15 / 1500.0, 1.66 / 1500.0};

    // Reads a .binary file; throws rsl::Error naming it (wrong dimensions,
    // truncated or oversized file, non-finite values).
    static std::shared_ptr<const MerlBrdf> load(const std::filesystem::path& path);

    // `raw`: 3 × kSamples values in file order and units (before kScale).
    MerlBrdf(const std::vector<double>& raw, std::filesystem::path source);

    Color eval(const Vec3& wi, const Vec3& wo) const override;
    bool isotropic() const override { return true; }
    std::string model() const override { return "merl"; }
    const std::filesystem::path& source() const { return source_; }

    // Samples any isotropic BRDF at the bin centers, in file order and units,
    // and writes such a table as a .binary file (through write_atomically).
    static std::vector<double> tabulate(const Brdf& brdf);
    static void save(const std::filesystem::path& path, const std::vector<double>& raw);

private:
    Color bin(int theta_h, int theta_d, int phi_d) const {
        return rgb_[(static_cast<size_t>(theta_h) * kThetaD + theta_d) * kPhiD + phi_d];
    }
    std::vector<Color> rgb_;  // scaled reflectance per bin, RGB interleaved
    std::filesystem::path source_;
};

}  // namespace rsl
