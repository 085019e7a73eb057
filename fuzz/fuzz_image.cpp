// Fuzzer of the environment-map readers (fuzz_hdr: Radiance .hdr, fuzz_exr:
// OpenEXR; RSL_FUZZ_EXTENSION picks the name the input gets). What `rsl fit`
// does with a map: read it (read_hdr_image), resample it to a cube map
// (load_environment) and fit a few lights to it (lightfit::decompose).
#include <cmath>

#include "fuzz/fuzz_support.h"
#include "src/formats/environment_file.h"
#include "src/lightfit/decompose.h"
#include "src/core/envmap.h"
#include "src/formats/image_file.h"

using namespace rsl;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::filesystem::path path = fuzz::write_input(data, size, RSL_FUZZ_EXTENSION);
    return fuzz::run_reader([&] {
        const Image image = read_hdr_image(path);
        RSL_FUZZ_EXPECT(image.width > 0 && image.height > 0 && (image.channels == 3 || image.channels == 4));
        RSL_FUZZ_EXPECT(image.pixels.size() == size_t(image.width) * image.height * image.channels);
        for (const float v : image.pixels)  // what check_radiance promises
            if (!(v >= 0.0f && v <= kMaxRadiance)) fuzz::finding("accepted a pixel value {}", v);
        const CubeMap map = load_environment(path, 4);
        for (int k = 0; k < map.texel_count(); ++k) {
            const Color c = map.radiance(k);
            if (!(c.r >= 0 && c.g >= 0 && c.b >= 0 && std::isfinite(c.r + c.g + c.b)))
                fuzz::finding("cube texel {} has radiance ({}, {}, {})", k, c.r, c.g, c.b);
        }
        // The fit costs most of a run: on a 6×2×2 map it still reaches every
        // sum the values enter, at a few hundred runs a second.
        const RslSet set = lightfit::decompose(load_environment(path, 2), {.lights = 4});
        for (const RotatableSquareLight& light : set.lights)
            if (!std::isfinite(light.half_diagonal + light.radiance.r + light.radiance.g + light.radiance.b))
                fuzz::finding("a fitted light has half-diagonal {} and radiance ({}, {}, {})", light.half_diagonal,
                              light.radiance.r, light.radiance.g, light.radiance.b);
    });
}
