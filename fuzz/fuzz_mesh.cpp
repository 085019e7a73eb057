// Fuzzer of the mesh readers (fuzz_obj, fuzz_gltf, fuzz_glb; RSL_FUZZ_EXTENSION
// picks the name the input gets): a bare mesh file loaded as a scene, as
// `rsl info`, `rsl render` and `rsl truth` load it (load_scene: load_obj or
// the glTF loader, then the default camera framed on the posed parts).
#include "fuzz/fuzz_support.h"
#include "src/core/scene.h"
#include "src/formats/scene_file.h"

using namespace rsl;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::filesystem::path path = fuzz::write_input(data, size, RSL_FUZZ_EXTENSION);
    return fuzz::run_reader([&] { fuzz::check_scene(load_scene(path)); });
}
