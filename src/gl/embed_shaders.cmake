# Embeds shaders/*.glsl into the rsl_gl library (an installed binary needs no
# source tree), and the GLSL part of the shading core
# (each topic src/shading/shading_core.h includes, between its
# RSL_GLSL_BEGIN/END markers, in that order) as "shading_core.glsl", which the host prepends to the shading pass. Sets RSL_EMBEDDED_SHADERS to the generated source file, which
# defines rsl::gl::embedded_shader(name) (src/gl/shader_sources.h).
file(GLOB RSL_SHADER_FILES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/shaders/*.glsl)
file(GLOB RSL_SHADING_FILES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/shading/*.h)
set(RSL_EMBEDDED_SHADERS ${PROJECT_BINARY_DIR}/generated/rsl_embedded_shaders.cpp)
add_custom_command(
  OUTPUT ${RSL_EMBEDDED_SHADERS}
  COMMAND ${CMAKE_COMMAND} -DOUTPUT=${RSL_EMBEDDED_SHADERS} -DSHADER_DIR=${PROJECT_SOURCE_DIR}/shaders
          -DSHADING_CORE=${PROJECT_SOURCE_DIR}/src/shading/shading_core.h
          -P ${PROJECT_SOURCE_DIR}/src/gl/embed_shaders_script.cmake
  DEPENDS ${RSL_SHADER_FILES} ${RSL_SHADING_FILES} ${PROJECT_SOURCE_DIR}/src/gl/embed_shaders_script.cmake
  COMMENT "Embedding GLSL shaders"
  VERBATIM)
