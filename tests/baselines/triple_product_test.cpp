// The wavelet triple product (Ng 2004) against brute-force texel sums and the
// ground truth; the BRDF slice tables against exact slices.
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <random>
#include <set>

#include <catch2/catch.hpp>

#include "src/image/error_metrics.h"
#include "tests/baselines/baseline_scenes.h"
#include "src/brdf/brdf.h"
#include "tools/baselines/haar.h"
#include "tools/baselines/prt.h"
#include "tools/baselines/triple.h"
#include "tools/baselines/triple_product.h"
#include "tests/random_cases.h"

using namespace rsl;
using namespace rsl::test;

namespace {

// Three random cube functions, in texels and in Haar coefficients, with their
// non-zero coefficient lists: `density` is the fraction of non-zero
// coefficients (1: dense texel noise).
struct RandomTriple {
    int n;
    std::vector<Color> a_texels, c_texels, a_coefficients, c_coefficients;
    std::vector<float> b_texels, b_coefficients;
    std::vector<int32_t> a_index, c_index;
    std::vector<uint32_t> b_index;

    RandomTriple(int resolution, double density, uint32_t seed) : n(resolution) {
        const size_t count = size_t(6) * n * n;
        std::mt19937 rng(seed);
        std::uniform_real_distribution<float> value(-1.0f, 1.0f);
        std::bernoulli_distribution keep(density);
        auto draw = [&] { return keep(rng) ? value(rng) : 0.0f; };
        a_coefficients.resize(count), c_coefficients.resize(count), b_coefficients.resize(count);
        for (size_t k = 0; k < count; ++k) {
            a_coefficients[k] = Color(draw(), draw(), draw());
            b_coefficients[k] = draw();
            c_coefficients[k] = Color(draw(), draw(), draw());
        }
        a_texels = inverse(a_coefficients), c_texels = inverse(c_coefficients);
        b_texels = b_coefficients;
        haar::inverse_cube(b_texels.data(), n, 1);
        for (size_t k = 0; k < count; ++k) {
            if (a_coefficients[k] != Color(0.0f)) a_index.push_back(int32_t(k));
            if (b_coefficients[k] != 0.0f) b_index.push_back(uint32_t(k));
            if (c_coefficients[k] != Color(0.0f)) c_index.push_back(int32_t(k));
        }
    }
    std::vector<Color> inverse(std::vector<Color> coefficients) const {
        haar::inverse_cube(reinterpret_cast<float*>(coefficients.data()), n, 3);
        return coefficients;
    }
    DVec3 brute_force() const {
        DVec3 sum(0.0);
        for (size_t k = 0; k < a_texels.size(); ++k) sum += DVec3(a_texels[k]) * double(b_texels[k]) * DVec3(c_texels[k]);
        return sum;
    }
    std::vector<Color> a_values() const {
        std::vector<Color> values;
        for (int32_t k : a_index) values.push_back(a_coefficients[size_t(k)]);
        return values;
    }
};

// |x − y| relative to the scale of the sum's terms (a random sum can nearly cancel).
double relative_to(const DVec3& x, const DVec3& y, double scale) { return glm::length(x - y) / std::max(scale, 1e-12); }

}  // namespace

TEST_CASE("Tripling coefficients: the Haar triple product is the texel sum Σ a b c", "[triple]") {
    for (int n : {1, 2, 4, 8}) {
        for (double density : {1.0, 0.3, 0.05}) {
            for (uint32_t seed : {1u, 2u, 3u}) {
                const RandomTriple triple(n, density, seed * 7919u + uint32_t(n));
                triple::PreparedLighting lighting(n);
                const std::vector<Color> a_values = triple.a_values();
                lighting.prepare(triple.a_index.data(), a_values.data(), a_values.size());
                DVec3 scale(0.0);
                for (size_t k = 0; k < triple.a_texels.size(); ++k)
                    scale += glm::abs(DVec3(triple.a_texels[k]) * double(triple.b_texels[k]) * DVec3(triple.c_texels[k]));
                const DVec3 expected = triple.brute_force();
                INFO("N = " << n << ", density " << density << ", seed " << seed);
                // The BRDF factor as a sparse list (either list may be the sparser) and as dense.
                for (bool dense_brdf : {false, true}) {
                    triple::Factors factors;
                    factors.visibility_dense = triple.b_coefficients.data();
                    factors.visibility_index = triple.b_index.data();
                    factors.visibility_count = triple.b_index.size();
                    factors.brdf_dense = triple.c_coefficients.data();
                    factors.brdf_index = dense_brdf ? nullptr : triple.c_index.data();
                    factors.brdf_count = triple.c_index.size();
                    const DVec3 got(triple::evaluate(lighting, factors));
                    CHECK(relative_to(got, expected, glm::length(scale)) < 1e-5);
                }
            }
        }
    }
}

TEST_CASE("Tripling coefficients: one triple at a time matches its texel sum (every case of the theorem)", "[triple]") {
    // Single coefficients a = e_i, b = e_j, c = e_l at N = 4 on one face: the
    // evaluation must give C_ijl for every (i, j, l), zero or not.
    const int n = 4, count = 6 * n * n;
    triple::PreparedLighting lighting(n);
    std::vector<float> b(count, 0.0f);
    std::vector<Color> c(count, Color(0.0f));
    int nonzero = 0;
    for (int32_t i = 0; i < n * n; ++i) {
        const Color one(1.0f);
        lighting.prepare(&i, &one, 1);
        std::vector<float> ti(count, 0.0f);
        ti[i] = 1.0f;
        haar::inverse_cube(ti.data(), n, 1);
        for (uint32_t j = 0; j < uint32_t(n * n); ++j)
            for (int32_t l = 0; l < n * n; ++l) {
                std::vector<float> tj(count, 0.0f), tl(count, 0.0f);
                tj[j] = 1.0f, tl[l] = 1.0f;
                haar::inverse_cube(tj.data(), n, 1), haar::inverse_cube(tl.data(), n, 1);
                double expected = 0;
                for (int k = 0; k < count; ++k) expected += double(ti[k]) * tj[k] * tl[k];
                b[j] = 1.0f, c[l] = Color(1.0f);
                triple::Factors factors{b.data(), &j, 1, c.data(), &l, 1};
                const double got = triple::evaluate(lighting, factors).r;
                b[j] = 0.0f, c[l] = Color(0.0f);
                if (std::abs(expected) > 1e-6) ++nonzero;
                INFO("i " << i << " j " << j << " l " << l);
                REQUIRE(got == Approx(expected).margin(1e-6));
            }
    }
    CHECK(nonzero > n * n);  // the check saw many non-zero tripling coefficients
}

namespace {

// The truth of the shadow scene (environment only) seen from `camera`.
GroundTruth shadow_truth(Scene& scene, const CubeMap& sky, const Vec3& camera) {
    scene.camera.position = camera;
    GroundTruthOptions options;
    options.local_lights = false;
    options.max_sample_share = 0.0f;  // the texel-centre sum the transports sample
    return GroundTruth(scene, sky, 0.0f, options);
}

TripleOptions exact_options() {
    TripleOptions options;
    options.visibility_drop = 0.0f;
    options.block_vertices = 17;  // several blocks, one partial
    return options;
}

}  // namespace

TEST_CASE("Triple product with every lighting term and the exact BRDF slice is the truth's glossy sum", "[triple]") {
    Scene scene = make_shadow_scene(true);
    const CubeMap sky = make_sky(16);
    const GroundTruth truth = shadow_truth(scene, sky, scene.camera.position);
    const std::vector<Color> reference = flatten(truth.shade_vertices());
    PrtOptions prt_options;
    prt_options.sh = prt_options.haar = false;
    prt_options.check_lighting = &sky;
    const PrtPrecompute prt = precompute_prt(truth, sky, prt_options);
    const TriplePrecompute pre = precompute_triple_visibility(truth, sky, exact_options());
    CHECK(pre.rays > 0);
    TripleRenderer renderer(pre, truth, nullptr);
    std::vector<Color> out;
    renderer.render(sky, sky.texel_count(), truth.camera_position(), out);
    CHECK(relative_l2(out, prt.texel_sum) < 1e-5);
    CHECK(relative_l2(out, reference) < 1e-5);
    // A few lighting terms are a real approximation.
    renderer.render(sky, 10, truth.camera_position(), out);
    CHECK(relative_l2(out, reference) > 1e-3);
}

TEST_CASE("Triple product: changing the view changes the result as the truth does, without new visibility", "[triple]") {
    Scene scene = make_shadow_scene(true);
    const CubeMap sky = make_sky(16);
    const Vec3 first_camera = scene.camera.position, second_camera(-2.5f, 1.5f, -1.0f);
    const GroundTruth first = shadow_truth(scene, sky, first_camera);
    const GroundTruth second = shadow_truth(scene, sky, second_camera);
    const std::vector<Color> first_truth = flatten(first.shade_vertices()), second_truth = flatten(second.shade_vertices());
    REQUIRE(relative_l2(first_truth, second_truth) > 0.05);  // the views do differ
    const TriplePrecompute pre = precompute_triple_visibility(first, sky, exact_options());
    TripleRenderer renderer(pre, first, nullptr);
    std::vector<Color> out;
    renderer.render(sky, sky.texel_count(), first_camera, out);
    CHECK(relative_l2(out, first_truth) < 1e-5);
    renderer.render(sky, sky.texel_count(), second_camera, out);
    CHECK(relative_l2(out, second_truth) < 1e-5);
}

TEST_CASE("BRDF slice tables: a slice at a tabulated normal and view is the exact slice", "[triple]") {
    const int n = 4;
    const CubeMap grid(n);
    std::vector<Vec3> directions;
    for (int k = 0; k < grid.texel_count(); ++k) directions.push_back(grid.texel_direction(k));
    TripleOptions options;
    options.normal_resolution = 2, options.view_resolution = 3, options.brdf_terms = grid.texel_count();
    const auto brdf = make_brdf(material("blinn_phong", {{"kd", {0.3f, 0.2f, 0.1f}}, {"ks", {0.5f, 0.5f, 0.5f}}, {"exponent", {20}}}));
    const BrdfSlices table(*brdf, directions, n, options);
    REQUIRE(table.slice_count() == 6 * 4 * 9);
    std::vector<Color> exact(directions.size());
    for (int s = 0; s < table.slice_count(); ++s) {
        INFO("slice " << s);
        REQUIRE(table.slice_of(table.normal(s), table.view(s)) == s);
        const Frame frame = Frame::from_normal(table.normal(s));
        brdf_slice(*brdf, frame, frame.to_local(table.view(s)), directions, exact.data());
        std::vector<Color> tabulated(directions.size(), Color(0.0f));
        for (int t = 0; t < table.count(s); ++t) tabulated[size_t(table.index(s)[t])] = table.value(s)[t];
        haar::inverse_cube(reinterpret_cast<float*>(tabulated.data()), n, 3);
        REQUIRE(relative_l2(tabulated, exact) < 1e-5);
    }
    // Fewer terms: the slice is cut (and only views differ for a glossy BRDF).
    options.brdf_terms = 8;
    const BrdfSlices cut(*brdf, directions, n, options);
    CHECK(cut.count(0) == 8);
    CHECK(cut.bytes() < table.bytes());
    const auto lambert = make_brdf(material("lambert", {{"albedo", {0.5f, 0.5f, 0.5f}}}));
    CHECK(BrdfSlices(*lambert, directions, n, options).views_per_side() == 1);
}

TEST_CASE("Triple product with tabulated slices is exact where the normals are on the table (Lambertian planes)", "[triple]") {
    Scene scene = make_shadow_scene(false);  // every normal +Y, a cube-face centre when R_n = 1
    const CubeMap sky = make_sky(16);
    const GroundTruth truth = shadow_truth(scene, sky, scene.camera.position);
    const std::vector<Color> reference = flatten(truth.shade_vertices());
    TripleOptions options = exact_options();
    options.normal_resolution = 1, options.brdf_terms = sky.texel_count();
    const TriplePrecompute pre = precompute_triple_visibility(truth, sky, options);
    const TripleBrdfTables tables = tabulate_part_brdfs(truth, pre, options);
    REQUIRE(tables.part.size() == 2);
    CHECK(tables.part[0] != tables.part[1]);  // two materials, two tables
    TripleRenderer renderer(pre, truth, &tables);
    std::vector<Color> out;
    renderer.render(sky, sky.texel_count(), truth.camera_position(), out);
    CHECK(relative_l2(out, reference) < 1e-5);
    // The same table with few BRDF terms: an approximation.
    options.brdf_terms = 16;
    const TripleBrdfTables cut = tabulate_part_brdfs(truth, pre, options);
    TripleRenderer cut_renderer(pre, truth, &cut);
    cut_renderer.render(sky, sky.texel_count(), truth.camera_position(), out);
    CHECK(relative_l2(out, reference) > 1e-3);
}

namespace {

// The environment texels' directions at resolution n (the slices' domain).
std::vector<Vec3> texel_directions(int n) {
    const CubeMap grid(n);
    std::vector<Vec3> directions;
    for (int k = 0; k < grid.texel_count(); ++k) directions.push_back(grid.texel_direction(k));
    return directions;
}

// The table's blend for a normal and view, dense (Haar coefficients), by BrdfSlices::accumulate.
std::vector<Color> blended(const BrdfSlices& table, const Vec3& normal, const Vec3& view, size_t texels,
                           SliceWeights& weights) {
    table.weights(normal, view, weights);
    std::vector<Color> dense(texels, Color(0.0f));
    std::vector<uint8_t> touched(texels, 0);
    std::vector<int32_t> list(texels);
    const size_t listed = table.accumulate(weights, dense.data(), touched.data(), list.data(), 0);
    for (size_t k = 0; k < texels; ++k) CHECK((dense[k] != Color(0.0f)) <= bool(touched[k]));  // every non-zero listed
    CHECK(listed == size_t(std::count(touched.begin(), touched.end(), uint8_t(1))));
    return dense;
}

// One slice of the table, dense (Haar coefficients).
std::vector<Color> tabulated(const BrdfSlices& table, int slice, size_t texels) {
    std::vector<Color> dense(texels, Color(0.0f));
    for (int t = 0; t < table.count(slice); ++t) dense[size_t(table.index(slice)[t])] = table.value(slice)[t];
    return dense;
}

// The exact slice of a tabulated normal's frame and view, Haar-transformed, every term.
std::vector<Color> exact_coefficients(const Brdf& brdf, const Vec3& normal, const Vec3& view,
                                      const std::vector<Vec3>& directions, int n) {
    std::vector<Color> dense(directions.size());
    const Frame frame = Frame::from_normal(normal);
    brdf_slice(brdf, frame, frame.to_local(view), directions, dense.data());
    haar::forward_cube(reinterpret_cast<float*>(dense.data()), n, 3);
    return dense;
}

std::shared_ptr<const Brdf> glossy_brdf() {
    return make_brdf(material("blinn_phong", {{"kd", {0.3f, 0.2f, 0.1f}}, {"ks", {0.5f, 0.5f, 0.5f}}, {"exponent", {20}}}));
}

}  // namespace

TEST_CASE("BRDF slice lookup: at a tabulated normal and view the bilinear blend is that slice", "[triple]") {
    const int n = 4;
    const std::vector<Vec3> directions = texel_directions(n);
    TripleOptions options;
    options.normal_resolution = 3, options.view_resolution = 3, options.brdf_terms = int(directions.size());
    const auto brdf = glossy_brdf();
    const BrdfSlices table(*brdf, directions, n, options);
    REQUIRE(table.lookup() == TripleLookup::bilinear);
    SliceWeights weights;
    for (int s = 0; s < table.slice_count(); ++s) {
        INFO("slice " << s);
        const std::vector<Color> got = blended(table, table.normal(s), table.view(s), directions.size(), weights);
        const int largest = int(std::max_element(weights.weight, weights.weight + weights.count) - weights.weight);
        REQUIRE(weights.slice[largest] == s);
        REQUIRE(weights.weight[largest] > 1.0f - 1e-5f);
        REQUIRE(relative_l2(got, tabulated(table, s, directions.size())) < 1e-5);
    }
}

TEST_CASE("BRDF slice lookup: halfway between two tabulated normals the blend is their average", "[triple]") {
    const int n = 4;
    const std::vector<Vec3> directions = texel_directions(n);
    TripleOptions options;
    options.normal_resolution = 4, options.view_resolution = 4, options.brdf_terms = int(directions.size());
    const CubeMap normals(options.normal_resolution);
    SliceWeights weights;
    SECTION("Lambertian: one view, the two slices' mean (inside a face and across a face edge)") {
        const auto lambert = make_brdf(material("lambert", {{"albedo", {0.5f, 0.7f, 0.2f}}}));
        const BrdfSlices table(*lambert, directions, n, options);
        const int a = normals.index(4, 1, 1);  // +Z face; its +s neighbour, and its −s neighbour across the edge
        for (const auto& [b, s] : {std::pair{normals.index(4, 2, 1), 0.0f}, std::pair{normals.index(4, 0, 1), -0.5f}}) {
            const std::vector<Color> got =
                blended(table, CubeMap::face_direction(4, s, -0.25f), Vec3(0, 0, 1), directions.size(), weights);
            REQUIRE(weights.count == 2);
            CHECK(weights.weight[0] == Approx(0.5f).margin(1e-5));
            CHECK(weights.weight[1] == Approx(0.5f).margin(1e-5));
            std::vector<Color> mean = tabulated(table, a, directions.size());
            const std::vector<Color> other = tabulated(table, b, directions.size());
            for (size_t k = 0; k < mean.size(); ++k) mean[k] = 0.5f * (mean[k] + other[k]);
            CHECK(relative_l2(got, mean) < 1e-5);
        }
        // On the edge itself: half the edge texel, half the texel across it (CubeMap::neighbors).
        const int edge = normals.index(4, 0, 1), across = normals.neighbors(edge)[0];
        blended(table, CubeMap::face_direction(4, -1.0f, -0.25f), Vec3(0, 0, 1), directions.size(), weights);
        REQUIRE(weights.count == 2);
        CHECK(std::set<int>{weights.slice[0], weights.slice[1]} == std::set<int>{edge, across});
        CHECK(weights.weight[0] == Approx(0.5f).margin(1e-5));
    }
    SECTION("Glossy: the weighted sum of the exact slices of the 2 normals x 2x2 views") {
        const auto brdf = glossy_brdf();
        const BrdfSlices table(*brdf, directions, n, options);
        const Vec3 normal = CubeMap::face_direction(2, 0.0f, 0.25f);  // +Y face, between (1, 2) and (2, 2)
        const Vec3 view = glm::normalize(normal + Vec3(0.4f, 0.3f, -0.2f));
        const std::vector<Color> got = blended(table, normal, view, directions.size(), weights);
        REQUIRE(weights.count == 8);
        std::vector<Color> expected(directions.size(), Color(0.0f));
        std::map<int, double> per_normal;
        for (int w = 0; w < weights.count; ++w) {
            const int slice = weights.slice[w];
            per_normal[slice / 16] += weights.weight[w];
            const std::vector<Color> exact = exact_coefficients(*brdf, table.normal(slice), table.view(slice), directions, n);
            for (size_t k = 0; k < exact.size(); ++k) expected[k] += weights.weight[w] * exact[k];
        }
        REQUIRE(per_normal.size() == 2);
        CHECK(per_normal.count(normals.index(2, 1, 2)) == 1);
        CHECK(per_normal.count(normals.index(2, 2, 2)) == 1);
        for (const auto& [index, weight] : per_normal) CHECK(weight == Approx(0.5).margin(1e-5));
        CHECK(relative_l2(got, expected) < 1e-5);
        // Not merely one of the slices: the blend differs from each by far more.
        for (int w = 0; w < weights.count; ++w)
            CHECK(relative_l2(got, tabulated(table, weights.slice[w], directions.size())) > 1e-2);
    }
}

namespace {

// The octahedral view grid's coordinates of a local view in the upper hemisphere (triple.cpp's map).
Vec2 octahedral(const Vec3& local) {
    const float sum = std::abs(local.x) + std::abs(local.y) + local.z;
    return Vec2(local.x - local.y, local.x + local.y) / sum;
}

}  // namespace

TEST_CASE("BRDF slice lookup: the weights sum to 1 and reproduce the direction inside the grids", "[triple]") {
    const int n = 2;
    const std::vector<Vec3> directions = texel_directions(n);
    TripleOptions options;
    options.normal_resolution = 5, options.view_resolution = 6, options.brdf_terms = 4;
    const BrdfSlices glossy(*glossy_brdf(), directions, n, options);
    const BrdfSlices lambert(*make_brdf(material("lambert", {{"albedo", {0.5f, 0.5f, 0.5f}}})), directions, n, options);
    std::mt19937 rng(44);
    std::normal_distribution<float> gauss;
    const auto random_direction = [&] { return glm::normalize(test::random_vec3(gauss, rng)); };
    int interior_views = 0;
    SliceWeights weights;
    for (int c = 0; c < 20000; ++c) {
        const Vec3 normal = random_direction(), view = random_direction();  // half the views below the horizon
        INFO("case " << c);
        for (const BrdfSlices* table : {&glossy, &lambert}) {
            table->weights(normal, view, weights);
            const int views = table->views_per_side();
            REQUIRE(weights.count >= 1);
            REQUIRE(weights.count <= (views == 1 ? 4 : 16));
            double sum = 0;
            std::map<int, double> per_normal;
            for (int w = 0; w < weights.count; ++w) {
                REQUIRE(weights.weight[w] > 0.0f);
                sum += weights.weight[w];
                per_normal[weights.slice[w] / (views * views)] += weights.weight[w];
            }
            REQUIRE(sum == Approx(1.0).margin(1e-5));
            if (views == 1) continue;
            // Bilinear weights reproduce a linear function: inside each normal's
            // view grid (away from the horizon's clamp) the weighted grid views'
            // coordinates are the view's own.
            for (const auto& [normal_index, normal_weight] : per_normal) {
                const Frame frame = Frame::from_normal(glossy.normal(normal_index * views * views));
                const Vec3 local = frame.to_local(view);
                if (local.z <= 0.0f) continue;
                const Vec2 target = octahedral(local);
                if (std::max(std::abs(target.x), std::abs(target.y)) > 1.0f - 1.0f / float(views)) continue;
                Vec2 mean(0.0f);
                for (int w = 0; w < weights.count; ++w)
                    if (weights.slice[w] / (views * views) == normal_index)
                        mean += weights.weight[w] * octahedral(frame.to_local(glossy.view(weights.slice[w])));
                REQUIRE(glm::length(mean / float(normal_weight) - target) < 1e-4f);
                ++interior_views;
            }
        }
    }
    CHECK(interior_views > 10000);
}

TEST_CASE("Triple product: the bilinear slice lookup is closer to the truth than the nearest (glossy)", "[triple]") {
    Scene scene = make_shadow_scene(true);
    const CubeMap sky = make_sky(16);
    const GroundTruth truth = shadow_truth(scene, sky, scene.camera.position);
    const std::vector<Color> reference = flatten(truth.shade_vertices());
    TripleOptions options = exact_options();
    options.normal_resolution = 4, options.view_resolution = 4, options.brdf_terms = 256;
    const TriplePrecompute pre = precompute_triple_visibility(truth, sky, options);
    double error[2];
    for (TripleLookup lookup : {TripleLookup::nearest, TripleLookup::bilinear}) {
        options.lookup = lookup;
        const TripleBrdfTables tables = tabulate_part_brdfs(truth, pre, options);
        TripleRenderer renderer(pre, truth, &tables);
        std::vector<Color> out;
        renderer.render(sky, sky.texel_count(), truth.camera_position(), out);
        error[int(lookup)] = relative_l2(out, reference);
    }
    INFO("nearest " << error[0] << ", bilinear " << error[1]);
    CHECK(error[1] < 0.5 * error[0]);
}
