#pragma once
// The C++ side of the shading core's common subset of C++ (glm) and GLSL 330
// (docs/design/GPU_DESIGN.md "The shading core"): the glm names and GLSL
// built-ins the shared functions call, and the two markers they carry. Every
// file of the shading core includes it; the GPU gets the files' text between
// their RSL_GLSL_BEGIN and RSL_GLSL_END markers instead, after the
// generated layout constants (src/gl/gpu_layout.h), which define kPi and
// kSqrt2 for it.
//
// Rules of the shared part, so that it compiles as both languages:
//  * glm type names (vec2, vec3, vec4, ivec4, uvec2, uint, mat3, mat4), functions of both
//    libraries (min, max, clamp, mix, abs, sqrt, log, sin, tan, dot, length,
//    normalize, cross), no swizzles (vec3(v) takes a vec4's first three);
//  * results are small structs filled member by member (GLSL has no
//    aggregate initializers; C++ has no `out` parameters): no references,
//    pointers, templates, overloads on constness or member initializers;
//  * float literals carry `f` (GLSL ≥ 1.30 accepts it), locals are not
//    `const` (GLSL 330 wants constant initializers there);
//  * RSL_SHARED before every function (C++: inline), RSL_CONST before
//    constants (C++: inline constexpr; GLSL: const).
#include <bit>
#include <cmath>
#include <numbers>

#include <glm/glm.hpp>

#define RSL_SHARED inline
#define RSL_CONST inline constexpr

namespace rsl::shading {

using vec2 = glm::vec2;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using ivec4 = glm::ivec4;
using uvec2 = glm::uvec2;
using uint = unsigned;
using mat3 = glm::mat3;
using mat4 = glm::mat4;
using glm::clamp;
using glm::cross;
using glm::dot;
using glm::length;
using glm::max;
using glm::min;
using glm::mix;
using glm::normalize;
using std::abs;
using std::log;
using std::sin;
using std::sqrt;
using std::tan;

// GLSL's bit reinterpretations (portable_log).
inline int floatBitsToInt(float x) { return std::bit_cast<int>(x); }
inline float intBitsToFloat(int x) { return std::bit_cast<float>(x); }

// π and √2 come from std::numbers; the GPU gets these values as generated
// constants (gpu_layout.h shader_constants_glsl), not as literals.
inline constexpr float kPi = std::numbers::pi_v<float>;
inline constexpr float kSqrt2 = std::numbers::sqrt2_v<float>;

}  // namespace rsl::shading
