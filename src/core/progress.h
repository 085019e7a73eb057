#pragma once
// Progress of long parallel loops (vertices, pixels).
#include <cstddef>
#include <functional>

namespace rsl {

// Called from worker threads (must be thread-safe) with the work done so far.
using ProgressCallback = std::function<void(size_t done, size_t total)>;

}  // namespace rsl
