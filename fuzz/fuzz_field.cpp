// Fuzzer of the field-file reader (.rslf, src/fields/field_file.h). The input's
// parameter hash and checksum are made right first (fuzz/fixup.h), so that
// mutations reach the parser; then the header is read as `rsl info` does and
// the field as the renderer does, and an accepted field is looked up.
#include <cmath>

#include "src/fields/field_file.h"
#include "fuzz/fixup.h"
#include "fuzz/fuzz_support.h"

using namespace rsl;

namespace {

void check_finite(float v, const char* what) {
    if (!std::isfinite(v)) fuzz::finding("an accepted field gives a non-finite {} ({})", what, v);
}

void look_up(const Svdf& svdf) {
    for (const int vertex : {0, svdf.vertex_count() - 1})
        for (const Vec2 p : {Vec2(0), Vec2(0.7f, -0.9f), Vec2(-1, 1)}) {
            check_finite(svdf.distance(vertex, p), "SVDF distance");
            check_finite(svdf.visible_fraction(vertex, p, 0.2f), "SVDF visible fraction");
        }
}

void look_up(const Ovdf& ovdf) {
    const Vec3 light = glm::normalize(Vec3(0.3f, 1, 0.2f));
    for (const float d : {0.5f, 1.0f, 2.0f, 4.0f, 8.0f}) {
        const Vec3 point = ovdf.center + d * ovdf.radius * glm::normalize(Vec3(1, 0.5f, -0.25f));
        for (const OvdfBlend blend : {OvdfBlend::AlignedCoefficients, OvdfBlend::AlignedSamples, OvdfBlend::SampleFrames})
            check_finite(ovdf.visible_fraction(point, light, 0.1f, blend), "OVDF visible fraction");
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::string bytes(reinterpret_cast<const char*>(data), size);
    fuzz::fix_field_file(bytes);
    const std::filesystem::path path = fuzz::write_input(bytes, ".rslf");
    return fuzz::run_reader([&] {
        const FieldHeader header = read_field_header(path);
        if (header.kind == FieldKind::Svdf) look_up(read_svdf(path));
        else look_up(read_ovdf(path));
    });
}
