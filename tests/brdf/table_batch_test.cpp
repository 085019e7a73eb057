// The vectorized batch lookup (brdf_table_lookup.cpp) against the lookup as
// documented, written out plainly from the public storage (lookup_data(),
// offset(), texel()): 16 corner taps per slice summed in double, or for a
// square up to three texels wide the texels it overlaps, views interpolated
// between all slices, for isotropic, anisotropic and view-independent tables,
// batch sizes that end mid-group and mid-block, and squares on the table's
// last row and column (the kernel's 8-float loads reach 2 floats past them).
#include <catch2/catch.hpp>

#include "src/brdf/brdf_table.h"
#include "tests/brdf/brdf_test_util.h"
#include "src/shading/brdf_sat.h"
#include "tests/random_cases.h"

using namespace rsl;
using namespace rsl::test;

namespace {

struct Reference {
    DVec3 value;
    double magnitude;  // Σ |terms| / area, every slice at weight 1: bounds float rounding
};

// Taps and view weights in float by the formulas of brdf_table.h (what any
// implementation must compute up to an ulp), the corner sums in double.
Reference reference_average(const BrdfTable& t, Vec2 c, float h, Vec3 view) {
    const int n = t.grid().n, v = t.options().view_samples;
    const float scale = 0.5f * float(n);
    h = std::max(h, shading::kMinSquareTexels / float(n));  // a square is read at least one texel wide
    float lo[2], hi[2];
    for (int d = 0; d < 2; ++d) {
        lo[d] = std::clamp((c[d] - h + 1.0f) * scale, 0.0f, float(n));
        hi[d] = std::clamp((c[d] + h + 1.0f) * scale, 0.0f, float(n));
    }
    const double clipped = double(hi[0] - lo[0]) * double(hi[1] - lo[1]);
    if (clipped <= 0.0) return {DVec3(0.0), 0.0};
    const double edge = 2.0 * h * scale;
    const bool small = 2.0f * h * scale <= shading::kMaxTexelSquareTexels;
    // Corner (index, weight) pairs along one axis: +upper edge, −lower edge.
    auto axis = [&](int d, int index[4], double weight[4]) {
        const int u = std::min(int(hi[d]), n - 1), l = std::min(int(lo[d]), n - 1);
        const double fu = hi[d] - float(u), fl = lo[d] - float(l);
        index[0] = u, index[1] = u + 1, index[2] = l, index[3] = l + 1;
        weight[0] = 1.0 - fu, weight[1] = fu, weight[2] = fl - 1.0, weight[3] = -fl;
    };
    int ax[4], by[4];
    double wx[4], wy[4];
    axis(0, ax, wx);
    axis(1, by, wy);
    auto lerp = [&](float x, int& k0, double& w) {
        x = std::clamp(x, 0.0f, float(v - 1));
        k0 = std::min(int(x), v - 2);
        w = x - float(k0);
    };
    std::vector<std::pair<int, double>> slices;
    if (t.isotropic()) {
        int k0;
        double w;
        lerp(std::sqrt(std::clamp(1.0f - view.z, 0.0f, 1.0f)) * float(v) - 0.5f, k0, w);
        slices = {{k0, 1.0 - w}, {k0 + 1, w}};
    } else {
        Vec2 p = hemisphere_to_plane(Vec3(view.x, view.y, std::max(view.z, -0.999f)));
        if (glm::dot(p, p) > 1.0f) p /= std::sqrt(glm::dot(p, p));
        int i0, j0;
        double wi, wj;
        lerp((p.x + 1.0f) * 0.5f * float(v) - 0.5f, i0, wi);
        lerp((p.y + 1.0f) * 0.5f * float(v) - 0.5f, j0, wj);
        slices = {{j0 * v + i0, (1 - wi) * (1 - wj)},
                  {j0 * v + i0 + 1, wi * (1 - wj)},
                  {(j0 + 1) * v + i0, (1 - wi) * wj},
                  {(j0 + 1) * v + i0 + 1, wi * wj}};
    }
    const size_t stride = size_t(n) + 1;
    const float* entries = t.lookup_data().data();
    DVec3 sum(0.0);
    double magnitude = 0.0;
    if (small) {  // each texel the square overlaps, by the overlap
        for (auto [s, weight] : slices)
            for (int j = 0; j < n; ++j)
                for (int i = 0; i < n; ++i) {
                    const double wx = std::max(0.0, std::min<double>(hi[0], i + 1) - std::max<double>(lo[0], i));
                    const double wy = std::max(0.0, std::min<double>(hi[1], j + 1) - std::max<double>(lo[1], j));
                    if (wx * wy == 0.0) continue;
                    const Color texel = t.texel(s, i, j);
                    sum += weight * wx * wy * DVec3(texel);
                    magnitude += wx * wy * (std::abs(texel.r) + std::abs(texel.g) + std::abs(texel.b));
                }
        return {sum / (edge * edge), magnitude / (edge * edge)};
    }
    for (auto [s, weight] : slices) {
        for (int m = 0; m < 4; ++m)
            for (int l = 0; l < 4; ++l) {
                const float* corner = entries + ((size_t(2 * s) * stride + by[m]) * stride + ax[l]) * 3;  // layer 0
                const double w = wx[l] * wy[m];
                for (int k = 0; k < 3; ++k) {
                    sum[k] += weight * w * corner[k];
                    magnitude += std::abs(w * corner[k]);
                }
            }
        sum += weight * clipped * DVec3(t.offset(s));
        magnitude += clipped * (std::abs(t.offset(s).r) + std::abs(t.offset(s).g) + std::abs(t.offset(s).b));
    }
    return {sum / (edge * edge), magnitude / (edge * edge)};
}

// Random squares (some partly or wholly off the table, some on its last row
// and column) and views (some below the horizon, some along the normal).
struct Batch {
    std::vector<float> cx, cy, h, vx, vy, vz;
};
Batch random_batch(size_t count, unsigned seed) {
    Batch b;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0, 1);
    for (size_t k = 0; k < count; ++k) {
        Vec2 c = 2.6f * test::random_vec2(u, rng) - 1.3f;
        const float h_draw = u(rng);
        float h = 0.002f + 0.3f * h_draw * u(rng);
        if (k % 7 == 3) c = 1.0f - 0.5f * h * test::random_vec2(u, rng);  // last row and column
        Vec3 view = random_upper_direction(rng);
        if (k % 11 == 5) view = Vec3(view.x, view.y, -0.2f * u(rng));   // below the horizon
        if (k % 13 == 6) view = Vec3(0.0f, 0.0f, 1.0f);                  // normal view
        if (k % 17 == 8) view = glm::normalize(Vec3(view.x, view.y, 1e-4f));  // grazing: last slices
        b.cx.push_back(c.x), b.cy.push_back(c.y), b.h.push_back(h);
        b.vx.push_back(view.x), b.vy.push_back(view.y), b.vz.push_back(view.z);
    }
    return b;
}

// Relative errors vs the reference where float rounding is not dominated by
// cancellation: squares of h ≥ 0.03 (about half a texel) and values of at
// least 1% of the table's largest texel.
struct RelativeErrors {
    double sum = 0, worst = 0;
    int count = 0;
    double mean() const { return count ? sum / count : 0.0; }
};

// Checks square_average_batch on a batch of `count` against the reference and
// the single lookup.
void check_batch(const BrdfTable& table, size_t count, unsigned seed, bool uniform_half_edge, RelativeErrors& errors) {
    const Batch b = random_batch(count, seed);
    std::vector<float> r(count), g(count), bl(count);
    SquareQueries q{b.cx.data(), b.cy.data(), b.h.data(), 0.0f, b.vx.data(), b.vy.data(), b.vz.data(), count};
    if (uniform_half_edge) q.half_edge = nullptr, q.uniform_half_edge = b.h.empty() ? 0.1f : b.h[0];
    table.square_average_batch(q, {r.data(), g.data(), bl.data()});
    float peak = 0;
    for (int s = 0; s < table.slice_count(); ++s)
        for (int j = 0; j < table.grid().n; ++j)
            for (int i = 0; i < table.grid().n; ++i) peak = std::max(peak, table.texel(s, i, j).g);
    for (size_t k = 0; k < count; ++k) {
        const float h = uniform_half_edge ? q.uniform_half_edge : b.h[k];
        const Vec2 c(b.cx[k], b.cy[k]);
        const Vec3 view(b.vx[k], b.vy[k], b.vz[k]);
        const Reference ref = reference_average(table, c, h, view);
        const Color got(r[k], g[k], bl[k]);
        // Float accumulation of ~10 terms per lane: a few ulps of the terms'
        // magnitude. A wrong corner, row, slice or weight is off by a texel
        // row's sum, orders of magnitude more.
        const double bound = 32 * 6e-8 * ref.magnitude + 1e-30;
        INFO("batch of " << count << ", query " << k << ": center " << c.x << "," << c.y << " h " << h << " view "
                         << view.x << "," << view.y << "," << view.z);
        for (int ch = 0; ch < 3; ++ch) {
            INFO("channel " << ch << ": got " << got[ch] << ", reference " << ref.value[ch] << ", bound " << bound);
            REQUIRE(std::abs(got[ch] - ref.value[ch]) <= bound);
            if (h >= 0.03f && ref.value[ch] >= 0.01 * peak) {
                const double e = std::abs(got[ch] - ref.value[ch]) / ref.value[ch];
                errors.sum += e, errors.worst = std::max(errors.worst, e), ++errors.count;
            }
        }
        // The single lookup is a batch of one: bit for bit the same.
        const Color one = table.square_average(c, h, view);
        REQUIRE(one.r == got.r);
        REQUIRE(one.g == got.g);
        REQUIRE(one.b == got.b);
    }
}

}  // namespace

TEST_CASE("batched lookups match the plain double-precision lookup, iso and aniso", "[brdf][table][batch]") {
    const std::vector<MaterialDesc> materials = {
        material("blinn_phong", {{"kd", {0.6f, 0.5f, 0.4f}}, {"ks", {0.25f}}, {"exponent", {30}}}),
        material("cook_torrance_ggx", {{"kd", {0.3f, 0.2f, 0.1f}}, {"f0", {0.9f, 0.6f, 0.3f}}, {"roughness", {0.2f}}}),
        material("phong", {{"ks", {1.0f}}, {"exponent", {500}}}),
        material("ward_anisotropic", {{"kd", {0.2f}}, {"ks", {0.6f}}, {"alpha_x", {0.1f}}, {"alpha_y", {0.3f}}}),
    };
    for (const MaterialDesc& m : materials)
        for (SatStorage storage : {SatStorage::FloatMeanOffset, SatStorage::Float}) {
            BrdfTableOptions options;
            options.storage = storage;
            const auto table = BrdfTable::build(*make_brdf(m), options);
            INFO(describe(m) << (storage == SatStorage::Float ? " plain float" : " mean offset"));
            REQUIRE_FALSE(table->view_independent());
            RelativeErrors errors;
            unsigned seed = 100;
            for (size_t count : {size_t(1), size_t(7), size_t(8), size_t(9), size_t(63), size_t(64), size_t(65), size_t(256), size_t(1000)})
                check_batch(*table, count, seed++, false, errors);
            check_batch(*table, 300, seed++, true, errors);
            // Measured mean 1e-7 to 2e-6 (the scalar lookup this kernel replaced:
            // up to 1.3× more), worst 4e-6 to 9e-5 near the horizon.
            INFO("relative error vs the double lookup: mean " << errors.mean() << ", worst " << errors.worst);
            CHECK(errors.count >= 20);
            CHECK(errors.mean() <= 1e-5);
        }
}

TEST_CASE("view-independent tables are detected from their texels and read one slice", "[brdf][table][batch]") {
    // Lambert, and Phong / Blinn-Phong without a lobe: every slice the same.
    for (const MaterialDesc& m : {material("lambert", {{"albedo", {0.8f, 0.5f, 0.3f}}}),
                                  material("phong", {{"kd", {0.4f}}, {"ks", {0.0f}}, {"exponent", {30}}}),
                                  material("blinn_phong", {{"kd", {0.7f, 0.6f, 0.5f}}, {"ks", {0.0f}}, {"exponent", {10}}})}) {
        INFO(describe(m));
        const auto table = BrdfTable::build(*make_brdf(m));
        REQUIRE(table->view_independent());
        // The reference interpolates between slices as for any isotropic table.
        RelativeErrors errors;
        unsigned seed = 300;
        for (size_t count : {size_t(1), size_t(9), size_t(64), size_t(65), size_t(500)})
            check_batch(*table, count, seed++, false, errors);
        INFO("relative error vs the double lookup: mean " << errors.mean() << ", worst " << errors.worst);
        CHECK(errors.mean() <= 1e-5);
    }
    // A lobe, however weak, depends on the view.
    const auto weak = BrdfTable::build(*make_brdf(material("phong", {{"kd", {0.4f}}, {"ks", {0.01f}}, {"exponent", {30}}})));
    CHECK_FALSE(weak->view_independent());
}
