#include "tools/rsl/data_folder.h"

#include <system_error>

namespace rsl::cli {

std::filesystem::path data_folder() {
    namespace fs = std::filesystem;
    std::error_code error;
    const fs::path program = fs::read_symlink("/proc/self/exe", error);
    if (!error) {
        const fs::path installed = program.parent_path().parent_path() / "share" / "rsl";
        if (fs::is_directory(installed / "demos", error)) return installed;
    }
    return RSL_SOURCE_DIR;
}

}  // namespace rsl::cli
