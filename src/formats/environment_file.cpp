// Environment files into cube maps: the file's envmap attribute, or else its
// shape, says whether it is a lat-long map or a cube strip.
#include "src/formats/environment_file.h"

#include <algorithm>
#include <cctype>
#include <string>

#include "src/core/error.h"
#include "src/formats/image_file.h"

namespace rsl {

namespace fs = std::filesystem;

CubeMap load_environment(const fs::path& path, int n) {
    if (n < 1 || n > 4096) throw_file_error(path, "cube map resolution {} is out of range 1..4096", n);
    const Image image = read_hdr_image(path);  // checks content vs extension, NaN/Inf/negative
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    const EnvmapKind declared = ext == ".exr" ? read_exr_envmap_kind(path) : EnvmapKind::None;
    const bool latlong_shape = image.width == 2 * image.height;
    const bool strip_shape = image.height == 6 * image.width;
    if (declared == EnvmapKind::Cube || (declared == EnvmapKind::None && strip_shape)) {
        if (!strip_shape)
            throw_file_error(path, "declared a cube map, but {}×{} is not a w×6w vertical strip", image.width,
                             image.height);
        return cube_from_strip(image, n);
    }
    if (declared == EnvmapKind::LatLong || latlong_shape) return cube_from_latlong(image, n);
    throw_file_error(path,
                     "{}×{} is neither a 2:1 latitude-longitude map nor a 1:6 vertical cube strip "
                     "(and the file has no envmap attribute saying which)",
                     image.width, image.height);
}

}  // namespace rsl

