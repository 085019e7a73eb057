// rsl as a library: a scene built in code (a floor and a ball under an
// environment map), the ball rolled across the floor for a few frames while
// the environment turns, the last frame written beside its ground truth.
//   embed ENVIRONMENT.exr OUT_FOLDER  →  OUT_FOLDER/{first,last,last_truth}.{exr,png}
#include <cmath>
#include <cstdio>
#include <string>

#include <rsl/rsl.h>

using namespace rsl::api;

// A floor of (n + 1)² vertices over [−half, half]², and a UV sphere.
Mesh floor_mesh(int n, float half) {
    Mesh mesh;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) mesh.positions.push_back({-half + 2 * half * i / n, 0, -half + 2 * half * j / n});
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const uint32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
            mesh.indices.insert(mesh.indices.end(), {a, c, b, b, c, d});
        }
    return mesh;
}

Mesh sphere_mesh(int rings, int segments, float radius) {
    Mesh mesh;
    for (int r = 0; r <= rings; ++r)
        for (int s = 0; s <= segments; ++s) {
            const float theta = 3.14159265f * r / rings, phi = 2 * 3.14159265f * s / segments;
            mesh.positions.push_back({radius * std::sin(theta) * std::cos(phi), radius * std::cos(theta),
                                      radius * std::sin(theta) * std::sin(phi)});
        }
    for (int r = 0; r < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            const uint32_t a = r * (segments + 1) + s, b = a + 1, c = a + segments + 1, d = c + 1;
            mesh.indices.insert(mesh.indices.end(), {a, b, c, b, d, c});
        }
    return mesh;  // the poles' zero-area triangles and the seam's unused twins are dropped by add_part
}

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: embed ENVIRONMENT.exr OUT_FOLDER\n");
        return 2;
    }
    const std::string out = argv[2];
    try {
        Scene scene("embed");
        scene.add_material({"floor", "lambert", {{"albedo", {0.6f, 0.58f, 0.55f}}}, ""});
        scene.add_material({"ball", "phong", {{"kd", {0.5f, 0.2f, 0.1f}}, {"ks", {0.3f, 0.3f, 0.3f}}, {"exponent", {20}}}, ""});
        scene.add_part("floor", floor_mesh(40, 1.0f), "floor");
        scene.add_part("ball", sphere_mesh(24, 48, 0.25f), "ball");
        scene.set_environment(argv[1], 16);
        scene.set_camera({{0.0f, 1.3f, 2.2f}, {0, 0.15f, 0}, {0, 1, 0}, 40, 160, 120});
        scene.set_precompute({16, 32, 4, 1, 6, 0.4f, 8.0f, 8, 16, 4});  // light settings: bakes in seconds

        RenderSettings settings;
        settings.field_cache = out + "/fields";  // baked once, reused by the next run
        Renderer renderer(scene, settings);
        const int frames = 8;
        for (int frame = 0; frame < frames; ++frame) {
            // Rolling along x: turned about z by distance / radius.
            const float x = -0.5f + frame * 0.14f, angle = -x / 0.25f;
            renderer.set_part_pose("ball", {{x, 0.25f, 0.1f}, {std::cos(angle / 2), 0, 0, std::sin(angle / 2)}, {1, 1, 1}});
            renderer.set_environment_rotation({0, 1, 0}, 15.0f * frame);
            const Image image = renderer.render_image();
            if (frame == 0) write_image(out + "/first.exr", image);
            if (frame == frames - 1) write_image(out + "/last.exr", image);
        }
        const VertexColors colors = renderer.shade(), truth = renderer.truth();
        write_image(out + "/last_truth.exr", renderer.form_image(truth));
        std::printf("embed: %zu vertices, %d frames; last frame against the ground truth: relative L2 %.4f\n",
                    colors.vertex_count(), frames, compare(colors, truth).relative_l2);
    } catch (const rsl::Error& e) {
        std::fprintf(stderr, "embed: error: %s\n", e.what());
        return 1;
    }
    return 0;
}
