#pragma once
// The CPU runtime renderer (RSL paper §3, Eq. 3–5; DESIGN.md "The rendering
// sum"): per vertex, per square light (the environment's RSLs, rotated with
// the environment, and every sphere light as a per-vertex square),
//
//   2r²·I  ×  BRDF-SAT average  ×  SVDF average  ×  Π_occluders OVDF average
//
// summed to an RGB vertex colour. The BRDF average is looked up in the
// view-aligned frame for isotropic tables and in the tangent frame for
// anisotropic ones; the SVDF in the tangent frame; each OVDF with the receiver
// point and the light direction moved into the occluder's frame.
//
// Work is split into blocks of vertices of one part; a block runs one light's
// lookups over all its vertices at a time (structure of arrays, a batch call
// into the BRDF table), blocks run on all cores. set_time() and shade() do not
// allocate once the first frame has sized the buffers.
#include <memory>
#include <vector>

#include "lightfit/rsl.h"
#include "src/core/envmap.h"
#include "src/core/scene.h"
#include "src/render/culling.h"
#include "src/render/material_tables.h"
#include "src/render/ovdf_lookup.h"
#include "src/render/part_fields.h"
#include "src/render/render_options.h"
#include "src/render/square_lights.h"
#include "src/frame/vertex_colors.h"

namespace rsl {

class Renderer {
public:
    // `scene` must outlive the renderer. `environment_lights` is the
    // environment's RSL set at rotation 0 (it is rotated by the environment's
    // rotation at every set_time; fit_environment_lights makes it). `fields`
    // may lack any field (that factor is then 1).
    Renderer(const Scene& scene, RslSet environment_lights, PartFields fields, const RenderOptions& options);

    // Poses parts, rotates the environment, moves lights and camera to time t,
    // and recomputes the occluder lists (culling).
    void set_time(float t);
    float time() const { return time_; }

    // Vertex colours of every part towards the camera; `out` must come from
    // make_output() (its buffers are reused, nothing is allocated).
    void shade(VertexColors& out);
    VertexColors make_output() const;
    VertexColors shade() {
        VertexColors out = make_output();
        shade(out);
        return out;
    }

    const RenderStats& stats() const { return stats_; }
    const RenderOptions& options() const { return options_; }
    const MaterialTables& materials() const { return materials_; }
    const RslSet& environment_lights() const { return rsls_; }
    // Square lights of the environment at the current time (world space).
    const std::vector<SquareLight>& environment_squares() const { return environment_squares_; }

private:
    struct Block {
        int part;
        int begin, end;  // vertex range
    };
    struct PartPose {
        Mat4 transform{1.0f};
        Mat3 linear{1.0f}, normal{1.0f};
        Mat4 inverse{1.0f};
        Mat3 inverse_linear{1.0f};
        // Lengths of inverse_linear's rows: a world direction w lies at
        // (inverse_linear·w)_a / face_scale_a from the part's box face a (the slab rule).
        Vec3 face_scale{1.0f};
        bool uniform_scale = true;  // the block-level cone test measures angles in the world
        BoundingSphere world_bounds;
    };
    struct BlockScratch;  // shade_block.cpp
    void update_occluder_lists();
    void shade_block(const Block& block, VertexColors& out, RenderStats& counts) const;
    void prepare_occluder(BlockScratch& s, const BoundingSphere& block_sphere, int occluder, bool culling) const;
    void prepare_occluder_vertices(BlockScratch& s, int occluder, int n, bool culling) const;
    void occluder_factors(BlockScratch& s, int part_index, int light, int occluder, int n, int m, bool per_occluder,
                          RenderStats& counts) const;

    const Scene& scene_;
    RenderOptions options_;
    RslSet rsls_;
    PartFields fields_;
    MaterialTables materials_;
    std::vector<Block> blocks_;
    std::vector<BoundingSphere> local_bounds_;       // per part, in its own frame
    std::vector<Bounds> local_boxes_;                // per part, in its own frame (the slab rule, square_lights.h)
    std::vector<BoundingSphere> local_reach_;        // per part: its occluder field's reach (radius 0: none)
    // Per part: the fast split lookup of its OVDF (null: the field's own lookup).
    std::vector<std::unique_ptr<const OvdfLookup>> fast_lookups_;

    float time_ = 0;
    std::vector<PartPose> poses_;
    std::vector<SquareLight> environment_squares_;
    std::vector<Vec3> light_positions_;
    std::vector<Color> light_radiance_;
    Vec3 camera_{0};
    // Per part: its field and pose as the occluder culling sees them.
    std::vector<CullingPart> culling_parts_;
    // Occluders that can shadow receiver part p for light l (culling.h, shared
    // with the GL renderer); the names below are its fields as shade_block.cpp
    // reads them: occluders_[offsets_[p·L + l] .. offsets_[p·L + l + 1]), and
    // per (receiver, occluder) the footprint growth of the receiver.
    OccluderLists occluder_lists_;
    std::vector<int>& occluders_ = occluder_lists_.occluders;
    std::vector<size_t>& offsets_ = occluder_lists_.offsets;
    std::vector<float>& occluder_growth_ = occluder_lists_.growth;
    RenderStats stats_;
};

// Checks `fields` against the scene's parts (an SVDF must have the mesh's
// vertex count) and gives it one entry per part (missing ones null).
void check_part_fields(const Scene& scene, PartFields& fields);

// The environment map fitted with K RSLs (lightfit, default options).
RslSet fit_environment_lights(const CubeMap& environment, int lights, bool cross_face = true);

}  // namespace rsl
