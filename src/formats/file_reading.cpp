#include "src/formats/file_reading.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "src/core/error.h"

namespace rsl {

namespace {

std::string type_of_mode(mode_t mode) {
    if (S_ISREG(mode)) return "a regular file";
    if (S_ISDIR(mode)) return "a directory";
    if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISSOCK(mode)) return "a socket";
    return "not a regular file";
}

[[noreturn]] void refuse_type(const std::filesystem::path& path, mode_t mode) {
    throw_file_error(path, "is {}, not a regular file", type_of_mode(mode));
}

// Closes the descriptor however the read ends.
struct FileDescriptor {
    int fd = -1;
    ~FileDescriptor() {
        if (fd >= 0) ::close(fd);
    }
};

// Opens a regular file for reading: stat first (no open of a FIFO at all),
// then O_NONBLOCK and fstat on what was opened, for a swap in between.
void open_regular(const std::filesystem::path& path, FileDescriptor& file, struct stat& info) {
    if (::stat(path.c_str(), &info) != 0) {
        if (errno == ENOENT || errno == ENOTDIR) throw_file_error(path, "does not exist");
        throw_file_error(path, "cannot read: {}", std::strerror(errno));
    }
    if (!S_ISREG(info.st_mode)) refuse_type(path, info.st_mode);
    file.fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (file.fd < 0) throw_file_error(path, "cannot open for reading: {}", std::strerror(errno));
    if (::fstat(file.fd, &info) != 0) throw_file_error(path, "cannot read: {}", std::strerror(errno));
    if (!S_ISREG(info.st_mode)) refuse_type(path, info.st_mode);
}

// Reads up to `count` bytes (fewer only at the end of the file).
size_t read_some(const std::filesystem::path& path, int fd, char* out, size_t count) {
    size_t got = 0;
    while (got < count) {
        const ssize_t n = ::read(fd, out + got, count - got);
        if (n == 0) break;
        if (n < 0) {
            if (errno == EINTR) continue;
            throw_file_error(path, "read error: {}", std::strerror(errno));
        }
        got += size_t(n);
    }
    return got;
}

}  // namespace

std::string why_not_regular_file(const std::filesystem::path& path) {
    struct stat info {};
    if (::stat(path.c_str(), &info) != 0)
        return errno == ENOENT || errno == ENOTDIR ? "does not exist" : fmt::format("cannot be read: {}", std::strerror(errno));
    return S_ISREG(info.st_mode) ? "" : fmt::format("is {}, not a regular file", type_of_mode(info.st_mode));
}

void check_regular_file(const std::filesystem::path& path) {
    FileDescriptor file;
    struct stat info {};
    open_regular(path, file, info);
}

std::string read_bounded_file(const std::filesystem::path& path, uint64_t max_bytes, std::string_view what,
                              std::string_view magic, std::string_view not_magic, const PieceCheck& check_piece) {
    FileDescriptor file;
    struct stat info {};
    open_regular(path, file, info);
    std::string bytes;
    if (!magic.empty()) {
        bytes.resize(magic.size());
        bytes.resize(read_some(path, file.fd, bytes.data(), bytes.size()));
        if (bytes != magic) throw_file_error(path, "{}", not_magic);
    }
    const uint64_t size = uint64_t(info.st_size);
    if (size > max_bytes)
        throw_file_error(path, "is {} bytes; {} may be at most {} bytes{}", size, what, max_bytes,
                         max_bytes >= kMiB ? fmt::format(" ({} MiB)", max_bytes / kMiB) : "");
    // Read in pieces up to one byte past the limit: a file that grows while
    // it is read is refused as well.
    constexpr size_t kPiece = size_t(1) << 20;
    bytes.reserve(size_t(size));
    if (check_piece && !bytes.empty()) check_piece(bytes, 0);
    for (;;) {
        const size_t at = bytes.size();
        const size_t want = size_t(std::min<uint64_t>(kPiece, max_bytes + 1 - std::min<uint64_t>(at, max_bytes)));
        bytes.resize(at + want);
        const size_t got = read_some(path, file.fd, bytes.data() + at, want);
        bytes.resize(at + got);
        if (check_piece && got > 0) check_piece(std::string_view(bytes).substr(at), at);
        if (bytes.size() > max_bytes)
            throw_file_error(path, "grew past {} bytes while read; {} may be at most {} bytes", max_bytes,
                             what, max_bytes);
        if (got < want) break;
    }
    return bytes;
}

std::string read_file_prefix(const std::filesystem::path& path, size_t count) {
    FileDescriptor file;
    struct stat info {};
    open_regular(path, file, info);
    std::string bytes(count, '\0');
    bytes.resize(read_some(path, file.fd, bytes.data(), count));
    return bytes;
}

std::string echo_value(std::string_view value) {
    if (value.substr(0, 5) == "data:") return fmt::format("a data: URI of {} bytes", value.size());
    if (value.size() <= kMaxEchoedBytes) return std::string(value);
    size_t cut = kMaxEchoedBytes - 1;
    while (cut > 0 && (static_cast<unsigned char>(value[cut]) & 0xC0) == 0x80) --cut;  // not inside a UTF-8 character
    return fmt::format("{}… ({} bytes)", value.substr(0, cut), value.size());
}

std::string echo_message(std::string_view message) {
    std::string out;
    for (size_t at = 0; at < message.size();) {
        const size_t end = std::min(message.find_first_of(" \t\n'\"", at), message.size());
        if (end == at) {
            out += message[at++];
            continue;
        }
        out += echo_value(message.substr(at, end - at));
        at = end;
    }
    return out;
}

}  // namespace rsl
