// fuzz_make_seeds [DIR]: writes the fuzzers' seed corpora (fuzz/seeds/seeds.h)
// into DIR (default: fuzz/corpus of this source tree), one folder per reader.
// The committed corpora are its output; rerun it when a format changes.
// fuzz_make_seeds --scene-files DIR: writes the files the scene seeds name
// into DIR (copy a scene seed there to read it with `rsl info`).
#include <cstdio>
#include <filesystem>
#include <string_view>

#include <fmt/core.h>

#include "fuzz/seeds/seeds.h"
#include "src/core/error.h"

int main(int argc, char** argv) {
    const std::filesystem::path source_dir = RSL_SOURCE_DIR;
    const std::filesystem::path dir = argc > 1 ? std::filesystem::path(argv[1]) : source_dir / "fuzz" / "corpus";
    try {
        if (argc == 3 && std::string_view(argv[1]) == "--scene-files") {
            rsl::fuzz::write_scene_support_files(argv[2]);
            return 0;
        }
        size_t bytes = 0;
        const auto files = rsl::fuzz::write_seed_corpora(dir, source_dir);
        for (const auto& file : files) bytes += std::filesystem::file_size(file);
        fmt::print("{} seeds, {} bytes, in {}\n", files.size(), bytes, dir.string());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "fuzz_make_seeds: %s\n", e.what());
        return 1;
    }
    return 0;
}
