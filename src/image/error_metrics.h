#pragma once
// Errors of a result A against a reference B (docs/design/METHOD.md "Ground truth and
// error"): relative L2 over vertices (RGB) or over covered pixels, maximum
// error, per-part breakdown, and for images an H1-type error on gradients.
#include <string>
#include <vector>

#include "src/core/image.h"
#include "src/formats/vertex_colors.h"

namespace rsl {

// Accumulates ‖A − B‖² and ‖B‖² over RGB elements, in double.
struct ErrorStats {
    double diff_squared = 0, reference_squared = 0;
    double max_error = 0;      // largest per-element RGB distance |a − b|
    double max_reference = 0;  // largest per-element |b|
    size_t count = 0;

    void add(const Color& a, const Color& b);
    // ‖A − B‖₂ / ‖B‖₂ (0 when both are 0; infinite when only B is).
    double relative_l2() const;
    // max |a − b| / max |b|.
    double relative_max() const;
    // The stats of both element sets together.
    void merge(const ErrorStats& other);
};

// ‖a − b‖₂ / ‖b‖₂ over two equally long lists of RGB values (ErrorStats):
// the one relative L2 error of every comparison, vertex lists and images alike.
double relative_l2(const std::vector<Color>& a, const std::vector<Color>& b);

struct VertexErrorReport {
    ErrorStats total;
    std::vector<std::string> part_names;
    std::vector<ErrorStats> parts;
};
// A and B must describe the same vertices (check_same_vertices). Parts both
// layered (textured) are compared at unit texture (diffuse + specular).
VertexErrorReport compare_vertex_colors(const VertexColors& a, const VertexColors& b);

// The static receivers of the project's scenes, a ground or a floor under
// the objects, and Blender's "Plane". A large receiver can make the
// all-vertex error look right while the objects on it are far off, so the
// objects are measured apart.
inline const std::vector<std::string> kDefaultReceivers = {"ground", "floor", "plane"};

// Whether part `name` is receiver `receiver`: the same name, ignoring case
// and an exporter's copy number (".001", "_2", "-3"), so that a glTF's
// "Plane" or "Floor.001" counts as the receiver it is.
bool is_receiver(const std::string& name, const std::string& receiver);

// The error of the objects: every part not named in `receivers`, together,
// and the worst of them (largest relative L2; empty name when no part is an
// object).
struct ObjectErrorReport {
    ErrorStats objects;
    size_t object_parts = 0;
    std::string worst_part;
    double worst = 0;
};
ObjectErrorReport object_errors(const VertexErrorReport& report,
                                const std::vector<std::string>& receivers = kDefaultReceivers);

// The one image error of the project (`rsl compare`, the demos, the
// baselines' tables; docs/design/TRUTH.md "Errors"): the pixels that count are those
// the reference B covers (alpha > 0; all pixels when B has no alpha), so a
// result is measured where the truth has a surface, and every method compared
// with one truth is measured over the same pixels.
struct ImageErrorReport {
    ErrorStats pixels;    // over the pixels B covers
    ErrorStats gradient;  // forward differences between neighbours B both covers
    size_t covered = 0, total = 0;
    double relative_h1() const { return gradient.relative_l2(); }
};
// Same size required (throws naming both); colours are compared as stored
// (premultiplied by coverage).
ImageErrorReport compare_images(const Image& a, const Image& b);

// Perceptually ordered false colour (dark blue → cyan → yellow → red) for x in
// [0, 1] (clamped), as linear RGB, so an sRGB PNG shows the intended colours.
Color false_color(float x);

// |a − b| per pixel (RGB distance) / scale in false colour; pixels covered by
// neither image stay black. scale ≤ 0 means the largest error.
Image error_image(const Image& a, const Image& b, float scale = 0);

}  // namespace rsl
