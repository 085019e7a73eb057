#pragma once
// The one shading core of the CPU and GPU renderers: every pure
// per-vertex × per-light function of the rendering sum (docs/design/RENDERER.md,
// docs/design/GPU_DESIGN.md), written once in the common subset of C++ (glm) and
// GLSL 330 (the rules: glsl_subset.h), one file per topic.
//
// C++ includes the topic it needs (namespace rsl::shading), or this header
// for all of them. The GPU gets each topic's text between its RSL_GLSL_BEGIN
// and RSL_GLSL_END markers, concatenated in the order of the includes below
// (src/gl/embed_shaders_script.cmake reads this list), after the layout
// constants generated from src/gl/gpu_layout.h. So a formula changed here
// changes both renderers; tests/gl/shading_core_test.cpp runs the functions
// on both and compares.
//
// What stays per side is data access (pointers and SoA loops on the CPU,
// texel fetches on the GPU) and the CPU's vectorized batch kernels.
//
// The topics depend on glm alone, so every layer of rsl, src/core included,
// may include them.
#include "src/shading/glsl_subset.h"
#include "src/shading/frames.h"
#include "src/shading/interpolation.h"
#include "src/shading/squares.h"
#include "src/shading/diffuse_light.h"
#include "src/shading/vdt.h"
#include "src/shading/brdf_sat.h"
#include "src/shading/pbr_basis.h"
#include "src/shading/ovdf_tables.h"
#include "src/shading/ovdf_small_occluder.h"
#include "src/shading/ovdf_inside.h"
#include "src/shading/shadow_maps.h"
#include "src/shading/ray_samples.h"
#include "src/shading/shapes.h"
#include "src/shading/culling.h"
