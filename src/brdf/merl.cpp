#include "src/brdf/merl.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>

#include "src/core/atomic_file.h"
#include "src/core/error.h"
#include "src/formats/file_reading.h"

namespace rsl {
namespace {

constexpr double kHalfPi = std::numbers::pi / 2.0;

// Rotation about the local y axis (the binormal of the half vector's frame).
DVec3 rotate_about_y(const DVec3& v, double angle) {
    const double c = std::cos(angle), s = std::sin(angle);
    return DVec3(v.x * c + v.z * s, v.y, v.z * c - v.x * s);
}
DVec3 rotate_about_z(const DVec3& v, double angle) {
    const double c = std::cos(angle), s = std::sin(angle);
    return DVec3(v.x * c - v.y * s, v.x * s + v.y * c, v.z);
}

struct HalfDiff {
    double theta_h, theta_d, phi_d;  // φ_d folded into [0, π)
};

// Rusinkiewicz coordinates of (ω_i, ω_o), as in the MERL reference reader.
HalfDiff half_diff(const Vec3& wi, const Vec3& wo) {
    const DVec3 in(wi), out(wo);
    const DVec3 h = glm::normalize(in + out);
    const double theta_h = std::acos(std::clamp(h.z, -1.0, 1.0));
    const double phi_h = std::atan2(h.y, h.x);
    const DVec3 d = rotate_about_y(rotate_about_z(in, -phi_h), -theta_h);
    const double theta_d = std::acos(std::clamp(d.z, -1.0, 1.0));
    double phi_d = std::atan2(d.y, d.x);
    if (phi_d < 0.0) phi_d += std::numbers::pi;
    return {theta_h, theta_d, phi_d};
}

// Continuous bin coordinate (bin k centered at k + ½) → lower bin and weight,
// clamped at both ends.
struct Lerp {
    int i0, i1;
    float w;
};
Lerp clamped_lerp(double u, int n) {
    const double t = std::clamp(u - 0.5, 0.0, static_cast<double>(n - 1));
    const int i0 = std::min(static_cast<int>(t), n - 2);
    return {i0, i0 + 1, static_cast<float>(t - i0)};
}
// φ_d is periodic with period π: bins wrap around.
Lerp periodic_lerp(double u, int n) {
    double t = u - 0.5;
    const double fl = std::floor(t);
    int i0 = static_cast<int>(fl) % n;
    if (i0 < 0) i0 += n;
    return {i0, (i0 + 1) % n, static_cast<float>(t - fl)};
}

}  // namespace

MerlBrdf::MerlBrdf(const std::vector<double>& raw, std::filesystem::path source)
    : rgb_(kSamples), source_(std::move(source)) {
    RSL_CHECK_EQ(raw.size(), static_cast<size_t>(3 * kSamples));
    for (int k = 0; k < kSamples; ++k)
        for (int c = 0; c < 3; ++c)
            rgb_[k][c] = static_cast<float>(std::max(raw[c * static_cast<size_t>(kSamples) + k], 0.0) * kScale[c]);
}

std::shared_ptr<const MerlBrdf> MerlBrdf::load(const std::filesystem::path& path) {
    check_regular_file(path);  // an ifstream would block on a FIFO
    std::ifstream in(path, std::ios::binary);
    if (!in) throw_file_error(path, "cannot open MERL BRDF for reading (missing or not readable)");
    int32_t dims[3] = {0, 0, 0};
    in.read(reinterpret_cast<char*>(dims), sizeof dims);
    if (in.gcount() != static_cast<std::streamsize>(sizeof dims))
        throw_file_error(path, "truncated MERL BRDF: the 12-byte header (three int32 dimensions) is incomplete");
    // The header's bytes are not echoed: the file may be any file at all (a key, a password list).
    if (dims[0] != kThetaH || dims[1] != kThetaD || dims[2] != kPhiD)
        throw_file_error(path, "not a MERL file (bad header: a MERL BRDF starts with the dimensions {}×{}×{})",
                         kThetaH, kThetaD, kPhiD);
    std::vector<double> raw(3 * static_cast<size_t>(kSamples));
    const auto expected = static_cast<std::streamsize>(raw.size() * sizeof(double));
    in.read(reinterpret_cast<char*>(raw.data()), expected);
    if (in.gcount() != expected)
        throw_file_error(path, "truncated MERL BRDF: {} bytes of samples, expected {}", in.gcount(), expected);
    if (in.peek() != std::char_traits<char>::eof())
        throw_file_error(path, "MERL BRDF has trailing bytes after its {} samples", raw.size());
    for (size_t k = 0; k < raw.size(); ++k)
        if (!std::isfinite(raw[k])) throw_file_error(path, "MERL BRDF sample {} is not finite ({})", k, raw[k]);
    return std::make_shared<MerlBrdf>(raw, path);
}

Color MerlBrdf::eval(const Vec3& wi, const Vec3& wo) const {
    if (wi.z <= 0.0f || wo.z <= 0.0f) return Color(0.0f);
    const HalfDiff a = half_diff(wi, wo);
    const Lerp h = clamped_lerp(std::sqrt(std::max(a.theta_h, 0.0) / kHalfPi) * kThetaH, kThetaH);
    const Lerp d = clamped_lerp(a.theta_d / kHalfPi * kThetaD, kThetaD);
    const Lerp p = periodic_lerp(a.phi_d / std::numbers::pi * kPhiD, kPhiD);
    auto along_phi = [&](int ih, int id) { return glm::mix(bin(ih, id, p.i0), bin(ih, id, p.i1), p.w); };
    auto along_d = [&](int ih) { return glm::mix(along_phi(ih, d.i0), along_phi(ih, d.i1), d.w); };
    return glm::mix(along_d(h.i0), along_d(h.i1), h.w);
}

std::vector<double> MerlBrdf::tabulate(const Brdf& brdf) {
    std::vector<double> raw(3 * static_cast<size_t>(kSamples));
    for (int ih = 0; ih < kThetaH; ++ih) {
        const double u = (ih + 0.5) / kThetaH;
        const double theta_h = u * u * kHalfPi;
        const DVec3 h(std::sin(theta_h), 0.0, std::cos(theta_h));
        for (int id = 0; id < kThetaD; ++id) {
            const double theta_d = (id + 0.5) / kThetaD * kHalfPi;
            for (int ip = 0; ip < kPhiD; ++ip) {
                const double phi_d = (ip + 0.5) / kPhiD * std::numbers::pi;
                const DVec3 d(std::sin(theta_d) * std::cos(phi_d), std::sin(theta_d) * std::sin(phi_d),
                              std::cos(theta_d));
                const DVec3 in = rotate_about_y(d, theta_h);  // undo the reader's rotation by −θ_h (φ_h = 0)
                const DVec3 out = 2.0 * glm::dot(in, h) * h - in;
                const Color value = brdf.eval(Vec3(in), Vec3(out));
                const size_t k = (static_cast<size_t>(ih) * kThetaD + id) * kPhiD + ip;
                for (int c = 0; c < 3; ++c) raw[c * static_cast<size_t>(kSamples) + k] = value[c] / kScale[c];
            }
        }
    }
    return raw;
}

void MerlBrdf::save(const std::filesystem::path& path, const std::vector<double>& raw) {
    RSL_CHECK_EQ(raw.size(), static_cast<size_t>(3 * kSamples));
    std::string bytes(12 + raw.size() * sizeof(double), '\0');
    const int32_t dims[3] = {kThetaH, kThetaD, kPhiD};
    std::memcpy(bytes.data(), dims, sizeof dims);
    std::memcpy(bytes.data() + sizeof dims, raw.data(), raw.size() * sizeof(double));
    write_file_atomically(path, bytes);
}

}  // namespace rsl
