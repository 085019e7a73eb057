#include "src/core/atomic_file.h"

#include <atomic>
#include <fstream>
#include <sstream>
#include <cerrno>
#include <csignal>
#include <system_error>

#include <sys/types.h>
#include <unistd.h>

#include "src/core/error.h"

namespace rsl {
namespace fs = std::filesystem;

namespace {

// The writer's process id in a temporary name ".STEM.tmp-PID-N.EXT" of
// `target`, or 0 when `name` is not one.
pid_t temporary_owner(const std::string& name, const fs::path& target) {
    const std::string prefix = fmt::format(".{}.tmp-", target.stem().string());
    const std::string extension = target.extension().string();
    if (name.size() <= prefix.size() + extension.size() || name.compare(0, prefix.size(), prefix) != 0 ||
        name.compare(name.size() - extension.size(), extension.size(), extension) != 0)
        return 0;
    const std::string middle = name.substr(prefix.size(), name.size() - prefix.size() - extension.size());
    const size_t dash = middle.find('-');
    if (dash == 0 || dash == std::string::npos || dash + 1 == middle.size()) return 0;
    if (middle.find_first_not_of("0123456789-") != std::string::npos) return 0;
    return pid_t(std::stol(middle.substr(0, dash)));
}

}  // namespace

void remove_stale_temporaries(const fs::path& path) {
    const fs::path parent = path.has_parent_path() ? path.parent_path() : fs::path(".");
    std::error_code ec;
    for (fs::directory_iterator it(parent, ec), end; !ec && it != end; it.increment(ec)) {
        const pid_t owner = temporary_owner(it->path().filename().string(), path);
        // Only a writer that no longer exists: a live one (this process's
        // other threads included) may be about to rename its file.
        if (owner <= 0 || owner == getpid() || !(::kill(owner, 0) != 0 && errno == ESRCH)) continue;
        std::error_code remove_error;
        fs::remove(it->path(), remove_error);
    }
}

void write_atomically(const fs::path& path, const std::function<void(const fs::path&)>& write) {
    static std::atomic<int> counter{0};
    const fs::path parent = path.has_parent_path() ? path.parent_path() : fs::path(".");
    std::error_code ec;
    fs::create_directories(parent, ec);
    if (ec) throw_file_error(parent, "cannot create directory: {}", ec.message());
    remove_stale_temporaries(path);
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
