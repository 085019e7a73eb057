#include "src/image/image_formation.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "src/core/emission.h"
#include "src/core/error.h"

namespace rsl {

PinholeCamera PinholeCamera::at_time(const Camera& camera, float t, int width, int height) {
    if (width <= 0 || height <= 0) throw_error("camera: image size {}×{} is empty", width, height);
    if (!(camera.fov_y_degrees > 0.0f && camera.fov_y_degrees < 180.0f))
        throw_error("camera: vertical field of view {}° is not in (0°, 180°)", camera.fov_y_degrees);
    PinholeCamera c;
    c.eye = camera.position_at(t);
    const Vec3 view = camera.target_at(t) - c.eye;
    if (!(glm::length(view) > 0.0f)) throw_error("camera: position and target coincide at t = {}", t);
    c.forward = glm::normalize(view);
    Vec3 right = glm::cross(c.forward, camera.up);
    if (!(glm::length(right) > 1e-6f)) right = any_orthonormal(c.forward);  // looking along `up`
    c.right = glm::normalize(right);
    c.up = glm::cross(c.right, c.forward);
    c.tan_half_fov_y = std::tan(0.5f * glm::radians(camera.fov_y_degrees));
    c.width = width;
    c.height = height;
    return c;
}

namespace {

constexpr int kPacket = RayScene::kPrimaryPacket;
// A tile is kTileSamples × kTileSamples samples (fewer pixels at more samples
// per pixel, at least one pixel), cut into packets of kPacketSide ×
// kPacketSide samples: square packets keep the packet's frustum narrow.
constexpr int kTileSamples = 8;
constexpr int kPacketSide = 4;
static_assert(kPacketSide * kPacketSide == kPacket);
constexpr int kMaxTilePixels = kTileSamples * kTileSamples;

// The tiles of an image at S×S samples per pixel: `side`×`side` pixels, in
// blocks of `block`×`block` pixels (one packet at S ≤ 4). Passed by value so
// that the hot loops keep it in registers.
struct TileLayout {
    int s, side, block, tiles_x, tiles_y, width, height;

    TileLayout(int samples_per_side, int image_width, int image_height)
        : s(samples_per_side),
          side(std::max(1, kTileSamples / s)),
          block(std::max(1, kPacketSide / s)),
          tiles_x((image_width + side - 1) / side),
          tiles_y((image_height + side - 1) / side),
          width(image_width),
          height(image_height) {}
    int count() const { return tiles_x * tiles_y; }
};

// The rays of one packet, as structure of arrays: pixel x + sample a / S
// (and y, b), the pixel in the tile, then the direction and the hit.
struct PacketScratch {
    int count = 0;
    // Whole packets go through the vector loops: no uninitialized lanes.
    int pixel_x[kPacket] = {}, sample_a[kPacket] = {}, pixel_y[kPacket] = {}, sample_b[kPacket] = {};
    uint8_t pixel[kPacket];
    alignas(64) float dx[kPacket];
    alignas(64) float dy[kPacket];
    alignas(64) float dz[kPacket];
    RayHit hits[kPacket];

    // Queues the S×S samples of pixel (x, y), number `p` in its tile, in
    // (b, a) order; traces whenever the packet is full.
    template <class Trace>
    void queue_pixel(int x, int y, int p, int s, Trace& trace) {
        for (int b = 0; b < s; ++b)
            for (int a = 0; a < s; ++a) {
                const int k = count++;
                pixel_x[k] = x, sample_a[k] = a, pixel_y[k] = y, sample_b[k] = b;
                pixel[k] = uint8_t(p);
                if (count == kPacket) trace();
            }
    }

    // The directions camera.direction gives, bit for bit: the same
    // expressions as glm::normalize, in loops the compiler vectorizes.
    void directions(const PinholeCamera& camera, int s) {
        alignas(64) float length[kPacket];
        for (int k = 0; k < kPacket; ++k) {
            const float sx = camera.screen_x(float(pixel_x[k]) + (float(sample_a[k]) + 0.5f) / float(s));
            const float sy = camera.screen_y(float(pixel_y[k]) + (float(sample_b[k]) + 0.5f) / float(s));
            const Vec3 v = camera.forward + sx * camera.right + sy * camera.up;
            dx[k] = v.x, dy[k] = v.y, dz[k] = v.z;
            length[k] = glm::dot(v, v);
        }
        sqrt_packet(length);
        for (int k = 0; k < kPacket; ++k) {
            const float inverse = 1.0f / length[k];
            dx[k] *= inverse, dy[k] *= inverse, dz[k] *= inverse;
        }
    }

    // In place, explicitly SIMD (the build's -fno-math-errno lets plain
    // loops vectorize too, but this one must not depend on the flags); the
    // SIMD square root is correctly rounded like the scalar one.
    static void sqrt_packet(float* values) {
#if defined(__AVX__)
        for (int k = 0; k < kPacket; k += 8) _mm256_store_ps(values + k, _mm256_sqrt_ps(_mm256_load_ps(values + k)));
#elif defined(__SSE2__)
        for (int k = 0; k < kPacket; k += 4) _mm_store_ps(values + k, _mm_sqrt_ps(_mm_load_ps(values + k)));
#else
        for (int k = 0; k < kPacket; ++k) values[k] = std::sqrt(values[k]);
#endif
    }
};

// Tiles in parallel; in a tile, blocks of pixels, pixels row by row, each
// pixel's samples in (b, a) order; a packet is traced whenever kPacket
// samples are queued, so a pixel's samples are summed in the order one ray at
// a time sums them.
template <bool kNormals, class Shade>
Image trace_tiles(const PosedScene& scene, const PinholeCamera& camera, const ImageFormationOptions& options,
                  const Shade& shade, const ProgressCallback& progress) {
    RSL_CHECK_GE(options.samples_per_side, 1);
    const TileLayout layout(options.samples_per_side, camera.width, camera.height);
    const size_t total_pixels = size_t(camera.width) * size_t(camera.height);
    Image image(camera.width, camera.height, 4);
    std::atomic<size_t> pixels_done{0};
    tbb::parallel_for(tbb::blocked_range<int>(0, layout.count()), [&](const tbb::blocked_range<int>& tiles) {
        const TileLayout tl = layout;
        const RayScene& rays = scene.rays();
        const float inv_samples = 1.0f / float(tl.s * tl.s);
        PacketScratch packet;
        Color sum[kMaxTilePixels];
        int covered[kMaxTilePixels];
        auto trace = [&] {
            packet.directions(camera, tl.s);
            rays.intersect_packet(camera.eye, packet.dx, packet.dy, packet.dz, packet.count, packet.hits, kNormals);
            for (int k = 0; k < packet.count; ++k) {
                const int p = packet.pixel[k];
                if (packet.hits[k].hit) {
                    sum[p] += shade(packet.hits[k], Vec3(packet.dx[k], packet.dy[k], packet.dz[k]));
                    ++covered[p];
                } else if (options.opaque_background) {
                    sum[p] += options.background;
                }
            }
            packet.count = 0;
        };
        for (int tile = tiles.begin(); tile != tiles.end(); ++tile) {
            const int x0 = (tile % tl.tiles_x) * tl.side, y0 = (tile / tl.tiles_x) * tl.side;
            const int w = std::min(tl.side, tl.width - x0), h = std::min(tl.side, tl.height - y0);
            std::fill(sum, sum + w * h, Color(0));
            std::fill(covered, covered + w * h, 0);
            for (int by = 0; by < h; by += tl.block)
                for (int bx = 0; bx < w; bx += tl.block)
                    for (int j = by; j < std::min(by + tl.block, h); ++j)
                        for (int i = bx; i < std::min(bx + tl.block, w); ++i)
                            packet.queue_pixel(x0 + i, y0 + j, j * w + i, tl.s, trace);
            if (packet.count > 0) trace();
            for (int j = 0; j < h; ++j) {
                float* out = image.at(x0, y0 + j);
                for (int i = 0; i < w; ++i, out += 4) {
                    const int p = j * w + i;
                    out[0] = sum[p].r * inv_samples;
                    out[1] = sum[p].g * inv_samples;
                    out[2] = sum[p].b * inv_samples;
                    out[3] = options.opaque_background ? 1.0f : float(covered[p]) * inv_samples;
                }
            }
            if (progress) {
                const size_t pixels = size_t(w) * size_t(h);
                progress(pixels_done.fetch_add(pixels) + pixels, total_pixels);
            }
        }
    });
    return image;
}

[[gnu::always_inline]] inline Color blend_vertex_colors(const Scene& scene, const VertexColors& colors,
                                                        const RayHit& hit) {
    const uint32_t* tri = &scene.parts[hit.instance].mesh.indices[3 * size_t(hit.triangle)];
    const Color* part = colors.parts[hit.instance].data();
    return (1.0f - hit.u - hit.v) * part[tri[0]] + hit.u * part[tri[1]] + hit.v * part[tri[2]];
}

}  // namespace

Vec2 interpolate_texcoords(const Scene& scene, const RayHit& hit) {
    const TriangleMesh& mesh = scene.parts[hit.instance].mesh;
    const uint32_t* tri = &mesh.indices[3 * size_t(hit.triangle)];
    return (1.0f - hit.u - hit.v) * mesh.texcoords[tri[0]] + hit.u * mesh.texcoords[tri[1]] +
           hit.v * mesh.texcoords[tri[2]];
}

Color interpolate_layered_colors(const Scene& scene, const VertexColors& colors, const Texture& texture,
                                 const RayHit& hit) {
    const TriangleMesh& mesh = scene.parts[hit.instance].mesh;
    const uint32_t* tri = &mesh.indices[3 * size_t(hit.triangle)];
    const float w0 = 1.0f - hit.u - hit.v;
    const Color* specular = colors.specular[hit.instance].data();
    return blend_vertex_colors(scene, colors, hit) * texture.lookup(interpolate_texcoords(scene, hit)) +
           (w0 * specular[tri[0]] + hit.u * specular[tri[1]] + hit.v * specular[tri[2]]);
}

const Texture* layer_texture(const Scene& scene, const VertexColors& colors, size_t part) {
    return part < colors.textures.size() && colors.textures[part]
               ? colors.textures[part].get()
               : scene.materials[size_t(scene.parts[part].material)].base_color_texture.get();
}

Image trace_image(const PosedScene& scene, const PinholeCamera& camera, const ImageFormationOptions& options,
                  const HitShader& shade, const ProgressCallback& progress) {
    return trace_tiles<true>(scene, camera, options, shade, progress);
}

Color interpolate_vertex_colors(const Scene& scene, const VertexColors& colors, const RayHit& hit) {
    return blend_vertex_colors(scene, colors, hit);
}

namespace {

bool emits(const VertexColors::PartEmission& e) { return rsl::emits(e.emissive); }

Color emission_at_hit(const Scene& scene, const VertexColors::PartEmission& e, const RayHit& hit) {
    return e.texture ? emission_at(e.emissive, e.texture.get(), interpolate_texcoords(scene, hit)) : e.emissive;
}

}  // namespace

std::vector<VertexColors::PartEmission> colors_emission(const Scene& scene, const VertexColors& colors) {
    std::vector<VertexColors::PartEmission> emission(scene.parts.size());
    for (size_t p = 0; p < scene.parts.size(); ++p) {
        const MaterialDesc& material = scene.materials[size_t(scene.parts[p].material)];
        emission[p] = p < colors.emission.size() ? colors.emission[p]
                                                 : VertexColors::PartEmission{material.emissive, material.emissive_texture};
        const TriangleMesh& mesh = scene.parts[p].mesh;
        if (emits(emission[p]) && emission[p].texture && mesh.texcoords.size() != mesh.vertex_count())
            throw_error("vertex colours of '{}': part '{}' has an emissive texture, the scene's part no texture "
                        "coordinates", colors.scene_name, scene.parts[p].name);
    }
    return emission;
}

bool any_emission(const Scene& scene, const VertexColors& colors) {
    const std::vector<VertexColors::PartEmission> emission = colors_emission(scene, colors);
    return std::any_of(emission.begin(), emission.end(), [](const auto& e) { return emits(e); });
}

VertexColors reflected_colors(const Scene& scene, const VertexColors& colors) {
    const std::vector<VertexColors::PartEmission> emission = colors_emission(scene, colors);
    VertexColors reflected = colors;
    for (size_t p = 0; p < emission.size() && p < colors.parts.size(); ++p) {
        if (!emits(emission[p])) continue;
        std::vector<Color>& layer = colors.layered(p) ? reflected.specular[p] : reflected.parts[p];
        const std::vector<Color> vertices = vertex_emission(emission[p].emissive, emission[p].texture.get(), scene.parts[p].mesh);
        RSL_CHECK_EQ(layer.size(), vertices.size());
        for (size_t v = 0; v < layer.size(); ++v) layer[v] -= vertices[v];
    }
    reflected.emission.assign(colors.parts.size(), {});
    return reflected;
}

Color hit_emission(const Scene& scene, const RayHit& hit) {
    const MaterialDesc& material = scene.materials[size_t(scene.parts[size_t(hit.instance)].material)];
    return emission_at_hit(scene, {material.emissive, material.emissive_texture}, hit);
}

Image form_image(const PosedScene& scene, const PinholeCamera& camera, const VertexColors& colors,
                 const ImageFormationOptions& options, const PartShaders& part_shaders) {
    const Scene& s = scene.scene();
    if (colors.parts.size() != s.parts.size())
        throw_error("vertex colours of '{}' have {} parts, scene '{}' has {}", colors.scene_name,
                    colors.parts.size(), s.name, s.parts.size());
    for (size_t p = 0; p < s.parts.size(); ++p)
        if (colors.parts[p].size() != s.parts[p].mesh.vertex_count())
            throw_error("vertex colours of '{}': part '{}' has {} values for {} vertices", colors.scene_name,
                        s.parts[p].name, colors.parts[p].size(), s.parts[p].mesh.vertex_count());
    // Layered parts: the texture comes with the colours, else from the scene's material.
    std::vector<const Texture*> textures(s.parts.size(), nullptr);
    bool any_layered = false;
    for (size_t p = 0; p < s.parts.size(); ++p) {
        if (!colors.layered(p)) continue;
        if (colors.specular[p].size() != colors.parts[p].size())
            throw_error("vertex colours of '{}': part '{}' has {} specular values for {} vertices", colors.scene_name,
                        s.parts[p].name, colors.specular[p].size(), colors.parts[p].size());
        textures[p] = layer_texture(s, colors, p);
        if (!textures[p] || s.parts[p].mesh.texcoords.size() != s.parts[p].mesh.vertex_count())
            throw_error("vertex colours of '{}': part '{}' is textured, the scene's part has no texture or no "
                        "texture coordinates", colors.scene_name, s.parts[p].name);
        any_layered = true;
    }
    auto shader_of = [&](const RayHit& hit) -> const HitShader* {
        const size_t p = size_t(hit.instance);
        return p < part_shaders.size() && part_shaders[p] ? &part_shaders[p] : nullptr;
    };
    // Emitting parts: what they reflect is blended, their emission taken at each sample.
    const std::vector<VertexColors::PartEmission> emission = colors_emission(s, colors);
    const bool emitting = std::any_of(emission.begin(), emission.end(), [](const auto& e) { return emits(e); });
    const VertexColors reflected = emitting ? reflected_colors(s, colors) : VertexColors{};
    const VertexColors& blended = emitting ? reflected : colors;
    // Barycentric interpolation needs no geometric normal.
    if (!any_layered && !emitting && part_shaders.empty())
        return trace_tiles<false>(scene, camera, options, [&](const RayHit& hit, const Vec3&) {
            return blend_vertex_colors(s, colors, hit);
        }, {});
    return trace_tiles<false>(scene, camera, options, [&](const RayHit& hit, const Vec3& direction) {
        const VertexColors::PartEmission& e = emission[size_t(hit.instance)];
        const Color emitted = emits(e) ? emission_at_hit(s, e, hit) : Color(0);
        if (const HitShader* shader = shader_of(hit)) return (*shader)(hit, direction) + emitted;
        if (const Texture* texture = textures[hit.instance])
            return interpolate_layered_colors(s, blended, *texture, hit) + emitted;
        return blend_vertex_colors(s, blended, hit) + emitted;
    }, {});
}

Image trace_image_one_ray_at_a_time(const PosedScene& scene, const PinholeCamera& camera,
                                    const ImageFormationOptions& options, const HitShader& shade) {
    const int s = options.samples_per_side;
    const float inv_samples = 1.0f / float(s * s);
    Image image(camera.width, camera.height, 4);
    tbb::parallel_for(tbb::blocked_range<int>(0, camera.height, 1), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y != rows.end(); ++y)
            for (int x = 0; x < camera.width; ++x) {
                Color sum(0);
                int covered = 0;
                for (int b = 0; b < s; ++b)
                    for (int a = 0; a < s; ++a) {
                        const Vec3 dir = camera.direction(float(x) + (float(a) + 0.5f) / float(s),
                                                          float(y) + (float(b) + 0.5f) / float(s));
                        const RayHit hit = scene.rays().intersect(camera.eye, dir);
                        if (hit.hit) {
                            sum += shade(hit, dir);
                            ++covered;
                        } else if (options.opaque_background) {
                            sum += options.background;
                        }
                    }
                float* pixel = image.at(x, y);
                for (int c = 0; c < 3; ++c) pixel[c] = sum[c] * inv_samples;
                pixel[3] = options.opaque_background ? 1.0f : float(covered) * inv_samples;
            }
    });
    return image;
}

Image resolve_samples(const Image& fine, int samples_per_side) {
    const int s = samples_per_side;
    RSL_CHECK_GE(s, 1);
    if (s == 1) return fine;
    RSL_CHECK(fine.width % s == 0 && fine.height % s == 0);
    Image image(fine.width / s, fine.height / s, fine.channels);
    const float weight = 1.0f / float(s * s);
    const size_t c = size_t(fine.channels);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            float* pixel = &image.pixels[(size_t(y) * size_t(image.width) + size_t(x)) * c];
            for (int b = 0; b < s; ++b)
                for (int a = 0; a < s; ++a) {
                    const float* sample = &fine.pixels[(size_t(y * s + b) * size_t(fine.width) + size_t(x * s + a)) * c];
                    for (size_t k = 0; k < c; ++k) pixel[k] += sample[k];
                }
            for (size_t k = 0; k < c; ++k) pixel[k] *= weight;
        }
    return image;
}

void fill_background(Image& image, const Color& background) {
    RSL_CHECK_EQ(image.channels, 4);
    for (size_t i = 0; i + 3 < image.pixels.size(); i += 4) {
        const float uncovered = 1.0f - image.pixels[i + 3];
        for (int k = 0; k < 3; ++k) image.pixels[i + size_t(k)] += uncovered * background[k];
        image.pixels[i + 3] = 1.0f;
    }
}

void fill_environment_background(Image& image, const PinholeCamera& camera, int samples_per_side,
                                 const CubeMap& environment, const Mat3& to_map) {
    RSL_CHECK_EQ(image.channels, 4);
    RSL_CHECK(image.width == camera.width && image.height == camera.height);
    const int s = samples_per_side;
    tbb::parallel_for(0, image.height, [&](int y) {
        for (int x = 0; x < image.width; ++x) {
            Color sum(0);
            for (int b = 0; b < s; ++b)
                for (int a = 0; a < s; ++a)
                    sum += environment.lookup(to_map * camera.direction(float(x) + (float(a) + 0.5f) / float(s),
                                                                        float(y) + (float(b) + 0.5f) / float(s)));
            float* pixel = image.at(x, y);
            const float uncovered = 1.0f - pixel[3];
            for (int k = 0; k < 3; ++k) pixel[k] += uncovered * sum[k] / float(s * s);
            pixel[3] = 1.0f;
        }
    });
}

}  // namespace rsl
