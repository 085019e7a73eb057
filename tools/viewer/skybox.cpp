#include "tools/viewer/skybox.h"

#include "src/core/error.h"

namespace rsl::gl {

namespace {

Texture upload_cube(const CubeMap& map) {
    Texture texture = make_texture();
    glBindTexture(GL_TEXTURE_CUBE_MAP, texture.id());
    const int n = map.resolution();
    // Face f, row j, column i is CubeMap::index(f, i, j): GL's texel (i, j) of that face.
    for (int face = 0; face < 6; ++face)
        glTexImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + face, 0, GL_RGB32F, n, n, 0, GL_RGB, GL_FLOAT,
                     &map.radiances()[size_t(map.index(face, 0, 0))].r);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        glTexParameteri(GL_TEXTURE_CUBE_MAP, wrap, GL_CLAMP_TO_EDGE);
    glBindTexture(GL_TEXTURE_CUBE_MAP, 0);
    check_gl("uploading the environment cube map");
    return texture;
}

GLint uniform(const Program& program, const char* name) { return glGetUniformLocation(program.id(), name); }

}  // namespace

Skybox::Skybox(const CubeMap& first, const CubeMap* second)
    : program_(build_program("skybox.vert.glsl", "skybox.frag.glsl", srgb_prelude())),
      first_(upload_cube(first)),
      second_(upload_cube(second ? *second : first)),
      vao_(make_vertex_array()) {
    glUseProgram(program_.id());
    glUniform1i(uniform(program_, "u_first"), kUnitSkyFirst);
    glUniform1i(uniform(program_, "u_second"), kUnitSkySecond);
    glUseProgram(0);
}

void Skybox::draw(const Mat4& view_projection, const Vec3& eye, const Mat3& rotation, float second_weight,
                  float exposure) {
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glUseProgram(program_.id());
    const Mat4 inverse = glm::inverse(view_projection);
    const Mat3 rotation_transpose = glm::transpose(rotation);
    glUniformMatrix4fv(uniform(program_, "u_inverse_view_projection"), 1, GL_FALSE, &inverse[0][0]);
    glUniform3fv(uniform(program_, "u_eye"), 1, &eye.x);
    glUniformMatrix3fv(uniform(program_, "u_rotation_transpose"), 1, GL_FALSE, &rotation_transpose[0][0]);
    glUniform1f(uniform(program_, "u_second_weight"), second_weight);
    glUniform1f(uniform(program_, "u_exposure"), exposure);
    glActiveTexture(GL_TEXTURE0 + kUnitSkyFirst);
    glBindTexture(GL_TEXTURE_CUBE_MAP, first_.id());
    glActiveTexture(GL_TEXTURE0 + kUnitSkySecond);
    glBindTexture(GL_TEXTURE_CUBE_MAP, second_.id());
    glBindVertexArray(vao_.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glActiveTexture(GL_TEXTURE0 + kUnitUpload);  // leave no pass's unit active
    glDepthMask(GL_TRUE);
    check_gl("the skybox pass");
}

}  // namespace rsl::gl
