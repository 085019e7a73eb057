#pragma once
// Base-colour textures (glTF baseColorTexture): a linear-RGB image sampled
// bilinearly at glTF texture coordinates with the sampler's wrap modes.
// Image formation (src/image) and the ground truth multiply a textured
// part's diffuse sum by it per pixel; the GL display pass samples the same
// texels with the same filter (docs/SCENE_FORMAT.md, "glTF materials").
#include <memory>
#include <string>

#include "src/core/image.h"

namespace rsl {

enum class TextureWrap { Repeat, ClampToEdge, MirroredRepeat };
// How `lookup` reads between texels (a glTF sampler's magFilter).
enum class TextureFilter { Bilinear, Nearest };

struct Texture {
    std::string name;  // for messages and `rsl info`: the image's name or URI
    Image image;       // RGB, linear (decoded from sRGB), row 0 at v = 0
    TextureWrap wrap_s = TextureWrap::Repeat, wrap_t = TextureWrap::Repeat;
    TextureFilter filter = TextureFilter::Bilinear;

    // Bilinear between texel centers: texel (i, j) is centred on
    // uv = ((i + ½)/W, (j + ½)/H), as in OpenGL.
    Color sample(const Vec2& uv) const;
    // The texel whose area holds uv (wrapped).
    Color sample_nearest(const Vec2& uv) const;
    // `sample` or `sample_nearest`, as `filter` says.
    Color lookup(const Vec2& uv) const { return filter == TextureFilter::Nearest ? sample_nearest(uv) : sample(uv); }
};

// The integer texel a wrap mode reads for index i of a row of n texels.
int wrap_texel(int i, int n, TextureWrap wrap);

// sRGB transfer function, decoding (glTF base colour images are sRGB).
float srgb_to_linear(float encoded);

}  // namespace rsl
