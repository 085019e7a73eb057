#pragma once
// The visibility fields the renderer multiplies in: per part, its SVDF (self-
// visibility, vertex frames) and an occluder field (the shadow it casts on the
// other parts, in its own frame).
//
// Occluder fields sit behind a small interface so that the renderer can use
// the compressed OVDF (src/fields/ovdf.h) or, for measuring the OVDF's own error,
// an exact stand-in.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "src/fields/svdf.h"
#include "src/core/mesh.h"
#include "src/core/scene.h"

namespace rsl {

class OccluderField {
public:
    virtual ~OccluderField() = default;
    // Visible fraction, as far as this part occludes, of the square of
    // half-edge `half_edge` around the unit direction `light`, seen from
    // `point`; both in the part's own frame.
    virtual float visible_fraction(const Vec3& point, const Vec3& light, float half_edge) const = 0;
    // In the part's frame: beyond this sphere the field is exactly 1 (the
    // outer shell), so a receiver outside it can skip the lookup.
    virtual BoundingSphere reach() const = 0;
    // How far from a receiver point the field's data may come from: a lookup
    // at a distance in [d_min, d_max] from the reach's center blends samples
    // within this distance of the point, so their shadows (not the point's
    // own) can darken it. Culling grows the receiver by it. 0 for an exact field.
    virtual float footprint(float d_min, float d_max) const { return 0.0f; }
};

// Per part, but per unique mesh in memory: parts whose meshes are equal
// (instances; src/fields/field_cache.h groups them) hold the same pointer, to a
// field baked in the mesh's own frame, and each part's transform poses it.
// PartFields is the name the renderer's API uses.
struct RenderFields {
    std::vector<std::shared_ptr<const Svdf>> self;               // per part; null: no self-visibility
    std::vector<std::shared_ptr<const OccluderField>> occluder;  // per part; null: casts no shadow
};
using PartFields = RenderFields;

// Field parameters from a scene's precompute settings (as `rsl bake` derives them).
SvdfParams svdf_params(const PrecomputeSettings& settings);

struct FieldBakeOptions {
    bool self_visibility = true;
    bool occluders = true;
    // Called with (what, fraction of that bake) from the baking threads.
    std::function<void(const std::string& what, double fraction)> progress;
    // The field cache folder for load_part_fields; empty: beside the scene's file.
    std::filesystem::path cache_directory;
};

// Bakes the fields of every unique mesh of `scene` with its precompute
// settings, in memory (no cache; for tests and scenes without a file).
PartFields bake_part_fields(const Scene& scene, const FieldBakeOptions& options);

// The fields from the scene's field cache (options.cache_directory, by default
// <scene folder>/.rsl-cache: the files `rsl bake` writes), baking and writing
// only the missing or stale ones, reporting to options.progress. A scene with neither a source file nor a cache folder
// is baked in memory; with neither field switched on, nothing is read or baked. Counts the field files reused and baked (one per unique
// mesh and kind, however many parts use the mesh).
struct FieldLoadReport {
    int loaded = 0, baked = 0;
};
PartFields load_part_fields(const Scene& scene, const FieldBakeOptions& options,
                            FieldLoadReport* report = nullptr);

}  // namespace rsl
