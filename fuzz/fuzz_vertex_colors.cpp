// Fuzzer of the per-vertex colour reader (.rslv, src/formats/vertex_colors.h).
// The checksum is made right first (fuzz/fixup.h) so that mutations reach
// the parser; an accepted file must write and read back the same.
#include <cmath>

#include "fuzz/fixup.h"
#include "fuzz/fuzz_support.h"
#include "src/formats/vertex_colors.h"

using namespace rsl;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    std::string bytes(reinterpret_cast<const char*>(data), size);
    fuzz::fix_trailing_checksum(bytes);
    const std::filesystem::path path = fuzz::write_input(bytes, ".rslv");
    return fuzz::run_reader([&] {
        const VertexColors colors = read_vertex_colors(path);
        RSL_FUZZ_EXPECT(colors.parts.size() == colors.part_names.size());
        const std::filesystem::path again = fuzz::scratch_dir() / "again.rslv";
        write_vertex_colors(again, colors);
        const VertexColors back = read_vertex_colors(again);
        RSL_FUZZ_EXPECT(back.scene_name == colors.scene_name && back.producer == colors.producer);
        RSL_FUZZ_EXPECT(back.part_names == colors.part_names && back.parts.size() == colors.parts.size());
        for (size_t p = 0; p < colors.parts.size(); ++p) {
            RSL_FUZZ_EXPECT(back.parts[p].size() == colors.parts[p].size());
            for (size_t v = 0; v < colors.parts[p].size(); ++v)
                RSL_FUZZ_EXPECT(back.parts[p][v] == colors.parts[p][v] && std::isfinite(colors.parts[p][v].r));
        }
    });
}
