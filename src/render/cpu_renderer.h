#pragma once
// The CPU runtime renderer (RSL paper §3, Eq. 3–5; docs/design/METHOD.md "The rendering
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
//
// It is a VertexRenderer (vertex_renderer.h): the frame state of time t comes
// from FrameSetup (frame_setup.h, shared with the GL renderer), the BRDF
// tables from a MaterialLibrary that can be edited between frames.
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "src/lightfit/square_light.h"
#include "src/core/envmap.h"
#include "src/core/scene.h"
#include "src/render/occluder_culling.h"
#include "src/render/frame_setup.h"
#include "src/render/ovdf_lookup.h"
#include "src/render/part_fields.h"
#include "src/render/occluder_shape.h"
#include "src/render/render_options.h"
#include "src/render/square_lights.h"
#include "src/formats/vertex_colors.h"
#include "src/render/vertex_blocks.h"
#include "src/render/vertex_renderer.h"

namespace rsl {

struct OccluderVertexScratch;  // shade_block.cpp

class CpuRenderer : public VertexRenderer {
public:
    // As VertexRenderer's constructor (vertex_renderer.h).
    CpuRenderer(const Scene& scene, EnvironmentLights environment_lights, PartFields fields,
                const RenderOptions& options);

    std::string backend() const override { return "cpu"; }

    // Vertex colours of every part towards the camera; `out` must come from
    // make_output() (its buffers are reused, nothing is allocated).
    void shade(VertexColors& out) override;
    using VertexRenderer::shade;

    // The shaders of the parts shaded per pixel, from `colors` (the last
    // shade()'s, with keep_image_terms on) for form_image at `posed` (the
    // scene posed at time()): what form_image() uses (pixel_shading.cpp).
    // They give what the surface reflects: form_image adds the emission.
    PartShaders pixel_shading(const VertexColors& colors, const PosedScene& posed) const;
    // Block b's (of blocks(), the GPU's too) candidate occluders'
    // lights after the block-level culling tests at the current frame: per
    // candidate of the block's part (OccluderLists::candidate_*, in order)
    // its light words, a bit per light the block still looks up. What the
    // GPU's workgroups compute (tests/gl compare the two).
    std::vector<uint32_t> block_candidate_lights(size_t b) const;
    size_t block_count() const { return blocks_.size(); }
    // Square lights of the environment at the current time (world space, blend-weighted).
    const std::vector<SquareLight>& environment_squares() const { return environment_squares_; }

protected:
    void lights_changed() override;
    // The kept terms are of the last frame: an image needs a new shade().
    void frame_changed() override { shaded_current_frame_ = false; }
    // The parts shaded per pixel (RenderOptions::pixel_shadows,
    // pixel_highlights) take the other parts' shadows and their own BRDF at
    // each pixel's point (pixel_shading.cpp); the rest blend vertex colours.
    Image backend_image(const VertexColors& colors, const PinholeCamera& camera,
                        const ImageFormationOptions& options) override;

private:
    using Block = VertexBlock;  // a range of the part's block_order_ (its vertices in compact blocks)
    struct BlockScratch;  // shade_block.cpp
    void sync_materials();
    void shade_block(const Block& block, VertexColors& out, RenderStats& counts);
    void load_block_points(BlockScratch& s, const Block& block) const;
    static BoundingSphere block_bounding_sphere(const BlockScratch& s, int n);
    // shade_block's phases (shade_block.cpp).
    struct PixelTerms;
    struct BlockPixelTerms {
        PixelTerms* terms = nullptr;  // null: the part is shaded per vertex
        bool unshadowed = false, specular = false, self = false;  // which of `terms` the part keeps
        const float* rim_floor = nullptr;  // highlights per pixel: brdf_queries' view_floor
    };
    BlockPixelTerms start_block_pixel_terms(BlockScratch& s, int part, bool textured, int n, size_t lights);
    void block_self_visibility(BlockScratch& s, int part, int light, const BrdfTable* specular, int m, bool keep_self,
                               RenderStats& counts) const;
    static void keep_block_pixel_terms(const BlockScratch& s, const BlockPixelTerms& kept, size_t lights, size_t l,
                                       int m);
    void set_point(BlockScratch& s, int k, const Vec3& position, const Frame& frame) const;
    void set_light(BlockScratch& s, size_t light, int n) const;
    void put_light(BlockScratch& s, int k, const SquareLight& square, float spot) const;
    void put_local_light(BlockScratch& s, int k, size_t local_light) const;
    void project_lights(BlockScratch& s, int n) const;
    void set_lights_at_point(BlockScratch& s, size_t lights) const;
    // The exact diffuse light's gains of the n points (s.gain_*; s.gains).
    void diffuse_light_gains(BlockScratch& s, int part, int n) const;
    // view_floor (per point k): points that face away from the camera with a
    // view cosine above view_floor[k] are queried too, with BRDF averages 0
    // (a part shaded with highlights per pixel keeps their self-visibility
    // and occluder factor: a pixel between a vertex beyond the silhouette and
    // the ones in front blends them).
    int brdf_queries(BlockScratch& s, const BrdfTable& table, const BrdfTable* specular, int n,
                     const float* view_floor = nullptr) const;
    // Parts whose roughness and metallic vary per point (src/brdf/pbr_basis.h):
    // the n points' weights on the basis tables (s.pbr), and the averages
    // brdf_queries takes from them in place of the part's table.
    void load_block_pbr(BlockScratch& s, int part, int n) const;
    void set_pbr_point(BlockScratch& s, int k, const Color& base, const PbrPoint& point) const;
    void pbr_averages(BlockScratch& s, const SquareQueries& queries, int m, bool layered) const;
    void shadow_by_occluders(BlockScratch& s, const BoundingSphere& block_sphere, int part, size_t light, int n,
                             int m, RenderStats& counts) const;
    void shadow_by_occluders(BlockScratch& s, const BoundingSphere& block_sphere, std::span<const int> occluders,
                             const float* growth, size_t light, int n, int m, RenderStats& counts) const;
    bool block_may_be_shadowed(BlockScratch& s, const BoundingSphere& block_sphere, int occluder, float growth,
                               size_t light) const;
    struct TriangleLights;  // pixel_shading.cpp
    Color shade_pixel(const VertexColors& colors, const PosedScene& posed, TriangleLights* cache, const RayHit& hit,
                      const Vec3& ray_direction) const;
    struct TriangleOccluders;  // pixel_shading.cpp
    void triangle_lights(BlockScratch& s, size_t part, const uint32_t* corner, uint64_t* mask,
                         TriangleOccluders& occluders) const;
    // shade_pixel's phases (pixel_shading.cpp).
    struct PixelOccluders;
    void triangle_shadowed_lights(BlockScratch& s, TriangleLights& cache, size_t part, size_t triangle,
                                  PixelOccluders& o) const;
    static void blend_dimmest_lights(const PixelTerms& terms, const uint32_t* corner, bool textured, float pixel_sum,
                                     PixelOccluders& o);
    float pixel_occlusion(BlockScratch& s, PixelOccluders& o, size_t l) const;
    Color pixel_highlights(BlockScratch& s, PixelOccluders& o, size_t part, const uint32_t* corner,
                           const float w[3]) const;
    Color pixel_shadows(BlockScratch& s, PixelOccluders& o, const PixelTerms& terms, const uint32_t* corner,
                        const float w[3], const Texture* texture, const RayHit& hit) const;
    void occluders_near(const BoundingSphere& sphere, size_t part, std::vector<int>& out) const;
    void prepare_occluder(BlockScratch& s, const BoundingSphere& block_sphere, int occluder, bool culling) const;
    OccluderVertexScratch& prepare_occluder_vertices(BlockScratch& s, int occluder, int n, bool culling) const;
    void occluder_factors(BlockScratch& s, OccluderVertexScratch& v, int light, int occluder, int n, int m,
                          RenderStats& counts) const;
    void ovdf_factors(BlockScratch& s, OccluderVertexScratch& v, int light, int occluder, int n,
                      RenderStats& counts) const;  // ovdf_factors.cpp

    // Per part: the table it is shaded with, refreshed from library_ before a
    // frame when a material's revision or a part's assignment changed.
    std::vector<const BrdfTable*> part_tables_;
    std::vector<const BrdfTable*> part_specular_tables_;  // null for untextured parts
    std::vector<Color> part_constant_terms_;  // per part: its (diffuse) BRDF's constant_part()
    // Per part whose material varies per point: each vertex's roughness and
    // metallic, and the base colour factor (empty, 0 for the others).
    std::vector<std::vector<PbrPoint>> part_pbr_points_;
    std::vector<Color> part_pbr_base_;
    std::vector<int> synced_material_;
    std::vector<uint64_t> synced_revision_;
    std::vector<Block> blocks_;
    // Per part: its vertices in the order they are shaded, runs of
    // kShadeBlock compact in space (vertex_blocks.h), so that culling per
    // block has a small sphere to test.
    std::vector<std::vector<int>> block_order_;
    std::vector<BoundingSphere> local_bounds_;       // per part, in its own frame
    std::vector<Bounds> local_boxes_;                // per part, in its own frame (the slab rule, square_lights.h)
    std::vector<OccluderShape> shapes_;              // per part: its exact shape, if any (occluder_shape.h)
    std::vector<BoundingSphere> local_reach_;        // per part: its occluder field's reach (radius 0: none)
    // Per part: the fast split lookup of its OVDF (null: the field's own lookup).
    std::vector<std::unique_ptr<const OvdfLookup>> fast_lookups_;
    // Per part, per vertex: the skinned segment whose OVDF the vertex leaves
    // out, -1 none; empty for a rigid part (skinning.h seam_partners).
    std::vector<std::vector<int>> seam_partners_;

    // The frame at time_ (VertexRenderer::frame_): its fields as shade_block.cpp reads them.
    const std::vector<PartPose>& poses_ = frame_.poses();
    const std::vector<SquareLight>& environment_squares_ = frame_.environment_squares();
    const std::vector<Vec3>& light_positions_ = frame_.light_positions();
    const std::vector<Vec3>& light_axes_ = frame_.light_axes();
    const Vec3& camera_ = frame_.camera();
    std::vector<Color> light_radiance_;
    std::vector<Vec2> light_cones_;  // spot_cone_scale_offset per local light
    // Occluders that can shadow receiver part p for light l (culling.h):
    // occluders_[offsets_[p·L + l] .. offsets_[p·L + l + 1]), and per
    // entry the footprint growth of the receiver by that occluder.
    const std::vector<int>& occluders_ = frame_.occluder_lists().occluders;
    const std::vector<size_t>& offsets_ = frame_.occluder_lists().offsets;
    const std::vector<float>& occluder_growth_ = frame_.occluder_lists().growth;
    // Sharp shadows on coarse receivers (RenderOptions::pixel_shadows): per
    // part shaded per pixel, the last shade()'s terms of every (vertex,
    // light), vertex-major: the light's share before the other parts'
    // shadows, and their factor. Empty for the parts shaded per vertex.
    // Parts with highlights per pixel (RenderOptions::pixel_highlights) keep
    // the SVDF factor (the visibility before the others' shadows) instead:
    // a pixel takes the BRDF at its own point.
    struct PixelTerms {
        std::vector<Color> unshadowed;          // shadows per pixel (a textured part: its diffuse layer)
        std::vector<Color> unshadowed_specular; // ... a textured part's specular layer
        std::vector<float> occlusion;           // either
        std::vector<float> self_visibility;     // highlights per pixel
    };
    std::vector<char> pixel_parts_;  // per part: shadows per pixel
    // Per part and vertex, for highlights per pixel: a vertex that faces away
    // from the camera by less than this view cosine still keeps its terms,
    // since a triangle it shares with a vertex facing the camera can be seen
    // (rim_view_floors; made at a part's first highlights).
    std::vector<std::vector<float>> rim_view_floor_;
    static std::vector<float> rim_view_floors(const TriangleMesh& mesh);
    // Per part and vertex, for highlights per pixel: 1 where the SVDF finds
    // the vertex enclosed by its own part (Svdf::enclosed_vertices), whose
    // share of a pixel's self-visibility blend goes to the other corners.
    std::vector<std::vector<uint8_t>> enclosed_vertices_;
    std::vector<PixelTerms> pixel_terms_;
    // form_image's preconditions: a shade() since the frame last changed,
    // which kept the image's terms.
    bool shaded_current_frame_ = false, terms_kept_ = false;
    // The scene posed at the image's time, whose hits the image's rays find
    // (made at the first image).
    std::unique_ptr<PosedScene> posed_;
};

}  // namespace rsl
