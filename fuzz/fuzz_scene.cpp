// Fuzzer of the JSON scene reader (docs/SCENE_FORMAT.md): the input is the
// scene file, written beside the small files the scene seeds name
// (fuzz/seeds: part.obj, part.glb, part.gltf, env.exr, env.hdr), then loaded
// and its materials built, as `rsl info` does.
#include "fuzz/fuzz_support.h"
#include "fuzz/seeds/seeds.h"
#include "src/brdf/brdf.h"
#include "src/core/scene.h"
#include "src/formats/scene_file.h"

using namespace rsl;

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    fuzz::silence_warnings();
    fuzz::write_scene_support_files(fuzz::scratch_dir());
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::filesystem::path path = fuzz::write_input(data, size, ".json");
    return fuzz::run_reader([&] {
        const Scene scene = load_scene(path);
        fuzz::check_scene(scene);
        RSL_FUZZ_EXPECT(make_scene_brdfs(scene).size() == scene.materials.size());
    });
}
