#pragma once
// The table `rsl info SCENE` and `rsl bake SCENE` print: the scene's unique
// meshes (fields are baked, stored and held once per unique mesh), how many
// parts use each, and each mesh's field files.
#include <cstdio>

#include "src/fields/field_cache.h"

namespace rsl::cli {

// One block per unique mesh: its name (first part's), vertices, instance
// count and part names (the first few), then per field kind what this run did
// (baked or read: seconds, disk and RAM bytes; another shard's) or, for a
// plan (plan_fields), whether the file is in the cache and its size.
void print_unique_meshes(std::FILE* out, const Scene& scene, const SceneFields& fields);

}  // namespace rsl::cli
