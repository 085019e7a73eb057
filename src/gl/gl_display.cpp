// The GL renderer's display pass and its per-pixel pass (gl_renderer.h),
// and the images they form offscreen (draw_image: `rsl render --backend gl`,
// the tests that hold the per-pixel pass to the CPU's).
#include <algorithm>
#include <cstdint>
#include <cmath>

#include "src/core/emission.h"
#include "src/core/error.h"
#include "src/brdf/pbr_basis.h"
#include "src/gl/gl_renderer.h"
#include "src/gl/gl_renderer_units.h"

namespace rsl::gl {

bool GlRenderer::highlight_part(size_t p) const {
    const size_t parts = scene_.parts.size();
    // With the ray-traced baseline every part is its vertex colours' blend, as the CPU's rays rows are.
    return options_.pixel_highlights && !options_.gpu_rays.enabled && part_tables_[parts + p] == nullptr &&
           library_.desc(library_.part_material(int(p))).model != "lambert";
}

bool GlRenderer::per_pixel_part(size_t p) const {
    return (options_.pixel_shadows != PixelShadows::Off && !options_.gpu_rays.enabled && rectangle_parts_[p]) ||
           highlight_part(p);
}

void GlRenderer::draw(const Mat4& view_projection, float exposure) {
    draw_parts(view_projection, exposure, false, GL_LESS);
}

void GlRenderer::draw_parts(const Mat4& view_projection, float exposure, bool linear, GLenum depth_test) {
    begin_pass(kPassDisplay);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(depth_test);
    glBindVertexArray(display_vao_.id());
    const auto& poses = frame_.poses();
    const size_t parts = scene_.parts.size();
    auto draw_elements = [&](size_t p) {
        const size_t count = first_index_[p + 1] - first_index_[p];
        glDrawElementsBaseVertex(GL_TRIANGLES, GLsizei(count), GL_UNSIGNED_INT,
                                 reinterpret_cast<const void*>(first_index_[p] * sizeof(uint32_t)),
                                 first_vertex_[p]);
    };
    // Layered as last shaded (the colour buffer's second rectangle holds its specular layer).
    auto layered_texture = [&](size_t p) -> GLuint {
        const std::shared_ptr<const rsl::Texture>& texture = library_.part_texture(int(p));
        return texture && part_tables_[parts + p] != nullptr ? base_color_texture(texture) : 0;
    };

    // Emission (src/core/emission.h): the colour buffer holds none, each
    // pixel adds the part's at its texture coordinates.
    auto bind_emission = [&](const Program& program, size_t p, int unit) {
        const MaterialDesc& m = library_.desc(library_.part_material(int(p)));
        const bool textured = emits(m) && m.emissive_texture;
        glUniform3f(uniform(program, "u_emissive"), m.emissive.r, m.emissive.g, m.emissive.b);
        glUniform1i(uniform(program, "u_emissive_textured"), textured ? 1 : 0);
        if (textured) bind_texture(unit, GL_TEXTURE_2D, uploaded_texture(m.emissive_texture, unit));
    };

    // The vertex colours' blend.
    glUseProgram(display_program_.id());
    glUniformMatrix4fv(uniform(display_program_, "u_view_projection"), 1, GL_FALSE, &view_projection[0][0]);
    glUniform1f(uniform(display_program_, "u_exposure"), exposure);
    glUniform1i(uniform(display_program_, "u_linear"), linear ? 1 : 0);
    const GLint model = uniform(display_program_, "u_model");
    const GLint textured = uniform(display_program_, "u_textured");
    glUniform1i(uniform(display_program_, "u_base_color"), kUnitDisplayBaseColor);
    glUniform1i(uniform(display_program_, "u_emissive_texture"), kUnitDisplayEmissive);
    bool any_per_pixel = false;
    for (size_t p = 0; p < parts; ++p) {
        if (per_pixel_part(p)) {
            any_per_pixel = true;
            continue;
        }
        glUniformMatrix4fv(model, 1, GL_FALSE, &poses[p].transform[0][0]);
        bind_emission(display_program_, p, kUnitDisplayEmissive);
        const GLuint texture = layered_texture(p);
        glUniform1i(textured, texture ? 1 : 0);
        if (texture) bind_texture(kUnitDisplayBaseColor, GL_TEXTURE_2D, texture);
        draw_elements(p);
    }

    // The per-pixel pass: the sum at each pixel's point, with the frame's
    // lights, occluder candidates and camera (the vertex pass's inputs),
    // compiled for the vertex pass's variant.
    if (any_per_pixel) {
        if (const VertexPassVariant variant = frame_vertex_pass_variant(); !pixel_program_ || variant != pixel_pass_variant_) {
            pixel_program_ = make_pixel_pass(variant);
            pixel_pass_variant_ = variant;
        }
        glUseProgram(pixel_program_.id());
        bind_shading_inputs(pixel_program_);
        glUniform1i(uniform(pixel_program_, "u_part_count"), int(scene_.parts.size()));
        glUniform1i(uniform(pixel_program_, "u_culling"), options_.occluder_culling ? 1 : 0);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingCandidates, candidates_.id());
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kBindingPartCulling, part_culling_.id());
        glUniformMatrix4fv(uniform(pixel_program_, "u_view_projection"), 1, GL_FALSE, &view_projection[0][0]);
        glUniform1f(uniform(pixel_program_, "u_exposure"), exposure);
        glUniform1i(uniform(pixel_program_, "u_linear"), linear ? 1 : 0);
        bind_texture(kUnitIndices, GL_TEXTURE_2D, indices_.texture.id());
        const GLint part = uniform(pixel_program_, "u_part");
        const GLint pixel_textured = uniform(pixel_program_, "u_textured");
        const GLint corners = uniform(pixel_program_, "u_corners");
        const GLint first_index = uniform(pixel_program_, "u_first_index");
        const GLint pbr_factor_uniform = uniform(pixel_program_, "u_pbr_factors");
        // A depth pre-pass first, so that the costly shading runs once per
        // pixel, for the nearest part (the robot's parts overlap on screen).
        const GLint depth_only = uniform(pixel_program_, "u_depth_only");
        glUniform1i(depth_only, 1);
        glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
        for (size_t p = 0; p < parts; ++p) {
            if (!per_pixel_part(p)) continue;
            glUniform1i(part, int(p));
            draw_elements(p);
        }
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glUniform1i(depth_only, 0);
        glDepthFunc(GL_EQUAL);
        for (size_t p = 0; p < parts; ++p) {
            if (!per_pixel_part(p)) continue;
            glUniform1i(part, int(p));
            // A rectangle cannot shadow itself; a glossy curved part blends its corners' SVDFs.
            glUniform1i(corners, rectangle_parts_[p] ? 0 : 1);
            glUniform1i(first_index, int(first_index_[p]));
            bind_emission(pixel_program_, p, kUnitEmissive);
            const GLuint texture = layered_texture(p);
            glUniform1i(pixel_textured, texture ? 1 : 0);
            if (texture) bind_texture(kUnitBaseColor, GL_TEXTURE_2D, texture);
            // A material varying per point: its texture at the pixel, times the factors.
            const MaterialDesc& material = library_.desc(library_.part_material(int(p)));
            if (varies_per_point(material)) {
                bind_texture(kUnitMetallicRoughness, GL_TEXTURE_2D,
                             uploaded_texture(material.metallic_roughness_texture, kUnitMetallicRoughness));
                const PbrPoint factors = pbr_factors(material);
                glUniform2f(pbr_factor_uniform, factors.roughness, factors.metallic);
            }
            draw_elements(p);
        }
        glDepthFunc(depth_test);
    }
    glBindVertexArray(0);
    end_pass(kPassDisplay);
    drew_[frame_parity_] = true;
    check_gl("the display pass");
}

Image GlRenderer::draw_image(const PinholeCamera& camera) {
    RSL_CHECK(camera.width > 0 && camera.height > 0);
    // Where the context has glClipControl (OpenGL 4.5: Mesa's llvmpipe, the
    // vendors' drivers), reversed Z into a float depth buffer: depth = near /
    // distance keeps a float's relative precision at every distance, so a
    // part 1 mm in front of another (the robot's visor on its head) stays in
    // front, as the CPU's rays see it, with the near plane very close.
    // Elsewhere, the usual depth from the nearest to the farthest of the
    // parts' posed boxes.
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    const bool reversed_z = major > 4 || (major == 4 && minor >= 5);
    float nearest = INFINITY, farthest = 0.0f;
    const auto& poses = frame_.poses();
    for (size_t p = 0; p < scene_.parts.size(); ++p) {
        const Bounds& box = part_bounds_[p];
        if (box.empty()) continue;  // no vertices
        const Vec3 &low = box.lo, &high = box.hi;
        for (int corner = 0; corner < 8; ++corner) {
            const Vec3 local((corner & 1) ? high.x : low.x, (corner & 2) ? high.y : low.y, (corner & 4) ? high.z : low.z);
            const float depth = glm::dot(Vec3(poses[p].transform * Vec4(local, 1.0f)) - camera.eye, camera.forward);
            nearest = std::min(nearest, depth), farthest = std::max(farthest, depth);
        }
    }
    farthest = std::max(farthest * 1.01f, 1e-3f);
    nearest = std::max(nearest * 0.99f, farthest * (reversed_z ? 1e-6f : 1e-4f));
    // PinholeCamera: image position (px, py) looks along forward + sx·right + sy·up.
    Mat4 view(1.0f);
    for (int i = 0; i < 3; ++i) view[i][0] = camera.right[i], view[i][1] = camera.up[i], view[i][2] = -camera.forward[i];
    view[3][0] = -glm::dot(camera.right, camera.eye);
    view[3][1] = -glm::dot(camera.up, camera.eye);
    view[3][2] = glm::dot(camera.forward, camera.eye);
    const float aspect = float(camera.width) / float(camera.height);
    Mat4 projection(0.0f);
    projection[0][0] = 1.0f / (camera.tan_half_fov_y * aspect);
    projection[1][1] = 1.0f / camera.tan_half_fov_y;
    projection[2][3] = -1.0f;  // w = distance along the view
    if (reversed_z) {          // z = near, so depth = near / distance (no far plane)
        projection[3][2] = nearest;
    } else {
        projection[2][2] = -(farthest + nearest) / (farthest - nearest);
        projection[3][2] = -2.0f * farthest * nearest / (farthest - nearest);
    }

    GLint previous_framebuffer = 0, previous_viewport[4] = {0, 0, 0, 0};
    glGetIntegerv(GL_FRAMEBUFFER_BINDING, &previous_framebuffer);
    glGetIntegerv(GL_VIEWPORT, previous_viewport);
    const Framebuffer framebuffer = make_framebuffer();
    const Texture color = make_texture();
    glActiveTexture(GL_TEXTURE0 + kUnitUpload);
    const Renderbuffer depth = make_renderbuffer();
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.id());
    glBindTexture(GL_TEXTURE_2D, color.id());
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, camera.width, camera.height, 0, GL_RGBA, GL_FLOAT, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, color.id(), 0);
    glBindRenderbuffer(GL_RENDERBUFFER, depth.id());
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, camera.width, camera.height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth.id());
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw Error("GL renderer: an RGBA32F image target is not renderable on this driver");
    const GLenum attachment = GL_COLOR_ATTACHMENT0;
    glDrawBuffers(1, &attachment);
    glViewport(0, 0, camera.width, camera.height);
    glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    glClearDepth(reversed_z ? 0.0 : 1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glDisable(GL_BLEND);
    if (reversed_z) glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    draw_parts(projection * view, 1.0f, true, reversed_z ? GL_GREATER : GL_LESS);
    if (reversed_z) glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    glClearDepth(1.0);
    glDepthFunc(GL_LESS);

    Image image(camera.width, camera.height, 4);
    std::vector<float> rows(image.pixels.size());
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glReadPixels(0, 0, camera.width, camera.height, GL_RGBA, GL_FLOAT, rows.data());
    glBindFramebuffer(GL_FRAMEBUFFER, GLuint(previous_framebuffer));
    glViewport(previous_viewport[0], previous_viewport[1], previous_viewport[2], previous_viewport[3]);
    check_gl("forming an image");
    // GL's first row is the bottom one.
    const size_t row = size_t(camera.width) * 4;
    for (int y = 0; y < camera.height; ++y)
        std::copy_n(&rows[size_t(camera.height - 1 - y) * row], row, &image.pixels[size_t(y) * row]);
    return image;
}

Image GlRenderer::backend_image(const VertexColors& colors, const PinholeCamera& camera,
                                const ImageFormationOptions& options) {
    // The display pass draws `colors` as shaded on the device: they must be
    // the last shade()'s (the CPU's image reads the same colours from them).
    RSL_CHECK_EQ(colors.vertex_count(), size_t(vertex_count_));
    if (!shaded_current_frame_) throw_error("form_image: the image needs a shade() of the current frame");
    // S×S samples per pixel: the image S times as large, whose pixel centres
    // are the CPU's sample positions, averaged (resolve_samples).
    const int s = options.samples_per_side;
    GLint max_texture = 0, max_renderbuffer = 0, max_viewport[2] = {0, 0};
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_texture);
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_renderbuffer);
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, max_viewport);
    const int64_t limit = std::min({int64_t(max_texture), int64_t(max_renderbuffer), int64_t(max_viewport[0]),
                                    int64_t(max_viewport[1])});
    if (int64_t(camera.width) * s > limit || int64_t(camera.height) * s > limit)
        throw_error("an image of {}×{} pixels at {}×{} samples is drawn {}×{} on the GPU; this driver draws at most "
                    "{} pixels a side (fewer samples, a smaller image, or the cpu backend)",
                    camera.width, camera.height, s, s, int64_t(camera.width) * s, int64_t(camera.height) * s, limit);
    PinholeCamera fine = camera;
    fine.width *= s;
    fine.height *= s;
    Image image = resolve_samples(draw_image(fine), s);
    if (options.opaque_background) fill_background(image, options.background);
    return image;
}

GLuint GlRenderer::base_color_texture(const std::shared_ptr<const rsl::Texture>& texture) {
    return uploaded_texture(texture, kUnitBaseColor);
}

GLuint GlRenderer::uploaded_texture(const std::shared_ptr<const rsl::Texture>& texture, int unit) {
    for (const auto& [source, uploaded] : base_colors_)
        if (source == texture) return uploaded.id();
    // Linear RGB(A) floats, row 0 at v = 0 as GL's first row; GL_LINEAR
    // without mipmaps is Texture::sample's bilinear between texel centers
    // (GL_NEAREST: sample_nearest).
    const Image& image = texture->image;
    RSL_CHECK(image.channels == 3 || image.channels == 4);  // the glTF loader decodes to RGB
    // Uploaded on the texture's own unit: binding it on whichever unit is
    // active would replace that unit's texture (the per-pixel pass's inputs).
    glActiveTexture(GLenum(GL_TEXTURE0 + unit));
    Texture uploaded = make_texture();
    glBindTexture(GL_TEXTURE_2D, uploaded.id());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage2D(GL_TEXTURE_2D, 0, image.channels == 4 ? GL_RGBA32F : GL_RGB32F, image.width, image.height, 0,
                 image.channels == 4 ? GL_RGBA : GL_RGB, GL_FLOAT, image.pixels.data());
    const GLint filter = texture->filter == TextureFilter::Nearest ? GL_NEAREST : GL_LINEAR;
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    auto wrap = [](TextureWrap w) {
        return w == TextureWrap::ClampToEdge ? GL_CLAMP_TO_EDGE
               : w == TextureWrap::MirroredRepeat ? GL_MIRRORED_REPEAT : GL_REPEAT;
    };
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, wrap(texture->wrap_s));
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, wrap(texture->wrap_t));
    check_gl("uploading a texture");
    base_colors_.emplace_back(texture, std::move(uploaded));
    return base_colors_.back().second.id();
}

}  // namespace rsl::gl
