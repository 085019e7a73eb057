#pragma once
// The fuzzers' seed corpora (docs/design/FUZZING.md), generated from the project's
// own generators and writers: small environment maps from
// tools/assets/environments, meshes from tools/assets/primitives, a
// two-node animated model through write_glb, the scene files of
// assets/scenes with their paths pointed at small stand-ins, field files
// baked on a small sphere, and vertex colours. Every seed is a valid input
// that the readers accept, a few KB at most, so that mutations start from
// the files' real structure.
#include <filesystem>
#include <string>
#include <vector>

namespace rsl::fuzz {

// The readers, in the order scripts/fuzz.sh runs them; the fuzzer of reader
// R is fuzz_R and its corpus fuzz/corpus/R/.
const std::vector<std::string>& reader_names();

// The file extension the reader R reads (".hdr", ..., ".rslv").
std::string reader_extension(const std::string& reader);

// Writes every corpus into `dir`/R/ (atomically, deterministic bytes);
// returns the files written. `source_dir` is the repository (for
// assets/scenes).
std::vector<std::filesystem::path> write_seed_corpora(const std::filesystem::path& dir,
                                                      const std::filesystem::path& source_dir);

// The files the scene seeds name, written into `dir`: part.obj, part.glb,
// part.gltf, env.exr (lat-long) and env.hdr. The scene fuzzer writes its
// input beside them; tests that read the scene seeds do the same.
void write_scene_support_files(const std::filesystem::path& dir);

}  // namespace rsl::fuzz
