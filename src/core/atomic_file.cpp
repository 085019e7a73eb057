#include "src/core/atomic_file.h"

#include <atomic>
#include <fstream>
#include <sstream>
#include <system_error>
#include <unistd.h>

#include "src/core/error.h"

namespace rsl {
namespace fs = std::filesystem;

void write_atomically(const fs::path& path, const std::function<void(const fs::path&)>& write) {
    static std::atomic<int> counter{0};
    const fs::path parent = path.has_parent_path() ? path.parent_path() : fs::path(".");
    std::error_code ec;
    fs::create_directories(parent, ec);
    if (ec) throw_file_error(parent, "cannot create directory: {}", ec.message());
    // Keep the target's extension last: some writers pick the format from it.
    const fs::path tmp = parent / fmt::format(".{}.tmp-{}-{}{}", path.stem().string(), getpid(),
                                              counter.fetch_add(1), path.extension().string());
    try {
        write(tmp);
    } catch (...) {
        fs::remove(tmp, ec);
        throw;
    }
    fs::rename(tmp, path, ec);
    if (ec) {
        fs::remove(tmp, ec);
        throw_file_error(path, "cannot rename temporary file into place: {}", ec.message());
    }
}

void write_file_atomically(const fs::path& path, std::string_view contents) {
    write_atomically(path, [&](const fs::path& tmp) {
        std::ofstream out(tmp, std::ios::binary);
        if (!out) throw_file_error(tmp, "cannot open for writing");
        out.write(contents.data(), static_cast<std::streamsize>(contents.size()));
        out.close();
        if (!out) throw_file_error(tmp, "write failed (disk full?)");
    });
}

std::string read_file(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw_file_error(path, "cannot open for reading (missing or not readable)");
    std::ostringstream buffer;
    buffer << in.rdbuf();
    if (in.bad()) throw_file_error(path, "read error");
    return std::move(buffer).str();
}

}  // namespace rsl
