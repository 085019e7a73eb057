#include "src/gl/shadow_map_pass.h"

#include <algorithm>
#include <cmath>

#include "src/core/error.h"

namespace rsl::gl {

namespace {

GLint uniform(const Program& program, const char* name) { return glGetUniformLocation(program.id(), name); }

}  // namespace

void check_shadow_map_options(const ShadowMapOptions& options) {
    if (options.resolution < ShadowMapOptions::kMinResolution || options.resolution > ShadowMapOptions::kMaxResolution)
        throw_error("shadow maps: resolution {} outside {}..{}", options.resolution, ShadowMapOptions::kMinResolution,
                    ShadowMapOptions::kMaxResolution);
    if (!(options.pcf_distance > 0.0f) || !std::isfinite(options.pcf_distance))
        throw_error("shadow maps: pcf_distance {} is not a positive fraction of the scene's radius",
                    options.pcf_distance);
}

Vec4 shadow_map_sphere(const std::vector<PartPose>& poses) {
    Bounds box;
    for (const PartPose& pose : poses) {
        box.extend(pose.world_bounds.center - Vec3(pose.world_bounds.radius));
        box.extend(pose.world_bounds.center + Vec3(pose.world_bounds.radius));
    }
    const Vec3 center = 0.5f * (box.lo + box.hi);
    float radius = 0.0f;
    for (const PartPose& pose : poses)
        radius = std::max(radius, glm::length(pose.world_bounds.center - center) + pose.world_bounds.radius);
    return Vec4(center, radius > 0.0f ? 1.01f * radius : 1.0f);
}

ShadowMaps::ShadowMaps() {
    program_ = build_program("shadow_depth.vert.glsl", "shadow_depth.frag.glsl", shading_prelude());
    framebuffer_ = make_framebuffer();
    check_gl("creating the shadow maps");
}

void ShadowMaps::allocate(int resolution, int layers) {
    GLint max_size = 0, max_layers = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &max_layers);
    if (resolution > max_size || layers > max_layers)
        throw_error("shadow maps: {} maps of {}² texels; this driver's array textures hold {} of at most {}²", layers,
                    resolution, max_layers, max_size);
    depths_ = make_texture();
    glBindTexture(GL_TEXTURE_2D_ARRAY, depths_.id());
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAX_LEVEL, 0);  // read by texelFetch only
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    while (glGetError() != GL_NO_ERROR) {}  // only this allocation's error below
    glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_DEPTH_COMPONENT32F, resolution, resolution, layers, 0,
                 GL_DEPTH_COMPONENT, GL_FLOAT, nullptr);
    if (glGetError() != GL_NO_ERROR) {
        depths_.reset();
        resolution_ = layers_ = 0;
        throw_error("shadow maps: the driver could not allocate {} maps of {}² depth texels ({:.0f} MiB)", layers,
                    resolution, double(resolution) * resolution * layers * 4 / (1 << 20));
    }
    glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
    resolution_ = resolution;
    layers_ = layers;
}

void ShadowMaps::render(int resolution, const std::vector<PartPose>& poses, const std::vector<SquareLight>& squares,
                        const ShadowCasters& casters) {
    const int layers = int(squares.size());
    if (layers == 0) return;
    if (resolution != resolution_ || layers != layers_) allocate(resolution, layers);
    sphere_ = shadow_map_sphere(poses);

    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
    glDrawBuffer(GL_NONE);
    glReadBuffer(GL_NONE);
    glViewport(0, 0, resolution_, resolution_);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    // Nothing lies outside the sphere, but a vertex on it may round past a
    // face: clamped, it still writes its depth.
    glEnable(GL_DEPTH_CLAMP);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);  // both faces cast: a mesh need not be closed
    glUseProgram(program_.id());
    glUniform4f(uniform(program_, "u_sphere"), sphere_.x, sphere_.y, sphere_.z, sphere_.w);
    const GLint light = uniform(program_, "u_light");
    const GLint model = uniform(program_, "u_model");
    glBindVertexArray(casters.vertex_array);
    const float far = 1.0f;
    for (int l = 0; l < layers; ++l) {
        glFramebufferTextureLayer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, depths_.id(), 0, l);
        if (l == 0 && glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            throw_error("shadow maps: a DEPTH_COMPONENT32F array layer is not renderable on this driver");
        glClearBufferfv(GL_DEPTH, 0, &far);
        const Vec3& direction = squares[size_t(l)].direction;
        glUniform3f(light, direction.x, direction.y, direction.z);
        for (size_t p = 0; p < poses.size(); ++p) {
            glUniformMatrix4fv(model, 1, GL_FALSE, &poses[p].transform[0][0]);
            const size_t count = casters.first_index[p + 1] - casters.first_index[p];
            glDrawElementsBaseVertex(GL_TRIANGLES, GLsizei(count), GL_UNSIGNED_INT,
                                     reinterpret_cast<const void*>(casters.first_index[p] * sizeof(uint32_t)),
                                     casters.first_vertex[p]);
        }
    }
    glBindVertexArray(0);
    glDisable(GL_DEPTH_CLAMP);
    glDisable(GL_DEPTH_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    check_gl("the shadow-map pass");
}

void ShadowMaps::bind_for_shading(const Program& shading, const ShadowMapOptions& options, int unit) const {
    glActiveTexture(GLenum(GL_TEXTURE0 + unit));
    glBindTexture(GL_TEXTURE_2D_ARRAY, depths_.id());
    glUniform1i(uniform(shading, "u_shadow_pcss"), options.filter == ShadowFilter::Pcss ? 1 : 0);
    glUniform4f(uniform(shading, "u_shadow_sphere"), sphere_.x, sphere_.y, sphere_.z, sphere_.w);
    glUniform1i(uniform(shading, "u_shadow_resolution"), resolution_);
    glUniform1f(uniform(shading, "u_shadow_texel"), 1.0f / float(resolution_));
    // pcf_distance × radius in the world; shadow_map_point scales by 0.5 / radius.
    glUniform1f(uniform(shading, "u_pcf_depth"), 0.5f * options.pcf_distance);
}

}  // namespace rsl::gl
