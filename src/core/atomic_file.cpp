#include "src/core/atomic_file.h"

#include <atomic>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstring>
#include <fstream>
#include <map>
#include <optional>
#include <random>
#include <sstream>
#include <system_error>

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/random.h>
#include <sys/types.h>
#include <unistd.h>

#include "src/core/checksum.h"
#include "src/core/error.h"

namespace rsl {
namespace fs = std::filesystem;

namespace {

std::string reason(int error) { return std::generic_category().message(error); }

uint64_t random_bits() {
    uint64_t bits = 0;
    if (::getrandom(&bits, sizeof(bits), 0) == ssize_t(sizeof(bits))) return bits;
    std::random_device device;  // getrandom missing (old kernel, seccomp)
    return (uint64_t(device()) << 32) ^ device();
}

// This boot of this machine and this PID namespace, as 16 hex digits: where
// two temporaries' tags are equal, their PIDs name the same processes.
// Computed on each call, since a fork into a new PID namespace changes it.
std::string host_tag() {
    std::string boot;
    std::getline(std::ifstream("/proc/sys/kernel/random/boot_id"), boot);
    char pid_namespace[64];
    const ssize_t length = ::readlink("/proc/self/ns/pid", pid_namespace, sizeof(pid_namespace));
    // Without /proc no PID can be judged: a random tag makes every other writer foreign (judged by age).
    if (boot.empty() || length <= 0) return fmt::format("{:016x}", random_bits());
    char host[256] = {};
    ::gethostname(host, sizeof(host) - 1);
    uint64_t hash = fnv1a64(boot.data(), boot.size());
    hash = fnv1a64(pid_namespace, size_t(length), hash);
    hash = fnv1a64(host, std::strlen(host), hash);
    return fmt::format("{:016x}", hash);
}

struct TemporaryName {
    std::string host;
    long pid = 0;
};

bool all_of(std::string_view text, const char* alphabet) {
    return !text.empty() && text.find_first_not_of(alphabet) == std::string_view::npos;
}

// The writer of a temporary named ".STEM.rsl-tmp-HOST-PID-RANDOM[.EXT]" (of
// any target); nullopt for any other name. The whole signature must match:
// a user's ".notes.tmp-2024-06.txt" is never taken for a temporary.
std::optional<TemporaryName> parse_temporary(std::string_view name) {
    if (name.size() < 2 || name[0] != '.') return std::nullopt;
    const std::string_view marker = kTemporaryMarker;
    for (size_t at = name.find(marker, 1); at != std::string_view::npos; at = name.find(marker, at + 1)) {
        std::string_view rest = name.substr(at + marker.size());
        rest = rest.substr(0, rest.find('.'));  // the extension follows the first dot
        std::vector<std::string_view> fields;
        for (size_t start = 0;;) {
            const size_t dash = rest.find('-', start);
            fields.push_back(rest.substr(start, dash - start));
            if (dash == std::string_view::npos) break;
            start = dash + 1;
        }
        const char* hex = "0123456789abcdef";
        const char* digits = "0123456789";
        if (fields.size() == 3 && fields[0].size() == 16 && all_of(fields[0], hex) && all_of(fields[1], digits) &&
            fields[1].size() <= 9 && fields[2].size() == 16 && all_of(fields[2], hex))
            return TemporaryName{std::string(fields[0]), std::stol(std::string(fields[1]))};
    }
    return std::nullopt;
}

// `text` cut to at most `bytes` bytes, never inside a UTF-8 sequence.
std::string utf8_prefix(const std::string& text, size_t bytes) {
    if (text.size() <= bytes) return text;
    while (bytes > 0 && (static_cast<unsigned char>(text[bytes]) & 0xC0) == 0x80) --bytes;
    return text.substr(0, bytes);
}

// ---------------------------------------------------------------- signals
// The temporaries this process is writing, for the SIGINT/SIGTERM handler:
// fixed slots, since a handler may only read memory and call unlink.
constexpr int kSlots = 64;
enum SlotState : int { kFree, kBusy, kLive };
struct Slot {
    std::atomic<int> state{kFree};
    char path[PATH_MAX];
};
static_assert(std::atomic<int>::is_always_lock_free, "the signal handler reads the slots' states");
Slot g_slots[kSlots];

extern "C" void remove_temporaries_and_reraise(int signal) {
    const int saved_errno = errno;
    for (Slot& slot : g_slots)
        if (slot.state.load() == kLive) ::unlink(slot.path);
    errno = saved_errno;
    // SA_RESETHAND put the default back: the signal, pending until this
    // handler returns, ends the process as it would have without us.
    ::raise(signal);
}

// Installs the handler for SIGINT and SIGTERM where the program left their
// default; a program's own handler (Python's KeyboardInterrupt, say) or an
// ignored signal stays as it is. Checked at every write, since a forked
// child or the program may have reset them.
void remove_temporaries_on_signals() {
    for (const int signal : {SIGINT, SIGTERM}) {
        struct sigaction current = {};
        if (::sigaction(signal, nullptr, &current) != 0 || (current.sa_flags & SA_SIGINFO) ||
            current.sa_handler != SIG_DFL)
            continue;
        struct sigaction ours = {};
        ours.sa_handler = remove_temporaries_and_reraise;
        sigemptyset(&ours.sa_mask);
        ours.sa_flags = SA_RESETHAND;
        ::sigaction(signal, &ours, nullptr);
    }
}

// A slot holding `path` (absolute, so a later chdir cannot misdirect the
// unlink), or -1 when all are taken or the path is too long: such a
// temporary is left to the sweep.
int register_temporary(const fs::path& path) {
    const std::string absolute = fs::absolute(path).string();
    if (absolute.size() >= PATH_MAX) return -1;
    for (int i = 0; i < kSlots; ++i) {
        int expected = kFree;
        if (!g_slots[i].state.compare_exchange_strong(expected, kBusy)) continue;
        std::memcpy(g_slots[i].path, absolute.c_str(), absolute.size() + 1);
        g_slots[i].state.store(kLive);
        return i;
    }
    return -1;
}

void unregister_temporary(int slot) {
    if (slot >= 0) g_slots[slot].state.store(kFree);
}

// ---------------------------------------------------------------- writing

// A temporary beside `target`, created exclusively (no other writer can share
// it), removed unless installed.
class Temporary {
public:
    explicit Temporary(const fs::path& target) : target_(target) {
        remove_temporaries_on_signals();
        for (int attempt = 0;; ++attempt) {
            path_ = temporary_path(target, long(::getpid()));
            slot_ = register_temporary(path_);
            fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
            if (fd_ >= 0) return;
            const int error = errno;
            unregister_temporary(slot_);
            if (error != EEXIST || attempt == 8)
                throw_file_error(target, "cannot create a temporary file in {}: {}", path_.parent_path().string(),
                                 reason(error));
        }
    }
    ~Temporary() {
        if (fd_ >= 0) ::close(fd_);
        if (!installed_) ::unlink(path_.c_str());
        unregister_temporary(slot_);
    }
    Temporary(const Temporary&) = delete;
    Temporary& operator=(const Temporary&) = delete;

    const fs::path& path() const { return path_; }

    void write(std::string_view bytes) {
        while (!bytes.empty()) {
            const ssize_t written = ::write(fd_, bytes.data(), bytes.size());
            if (written < 0 && errno == EINTR) continue;
            if (written <= 0) throw_file_error(target_, "cannot write: {}", reason(written < 0 ? errno : ENOSPC));
            bytes.remove_prefix(size_t(written));
        }
    }
    // Some file systems (NFS, quotas) report a failed write only here.
    void close() {
        const int fd = fd_;
        fd_ = -1;
        if (::close(fd) != 0 && errno != EINTR) throw_file_error(target_, "cannot write: {}", reason(errno));
    }
    void install() {
        if (::rename(path_.c_str(), target_.c_str()) != 0)
            throw_file_error(target_, "cannot move the written file into place: {}", reason(errno));
        installed_ = true;
    }

private:
    fs::path target_, path_;
    int fd_ = -1, slot_ = -1;
    bool installed_ = false;
};

// The folder of `path`, created if needed, with its orphaned temporaries swept.
void prepare_folder(const fs::path& path) {
    const fs::path parent = path.has_parent_path() ? path.parent_path() : fs::path(".");
    std::error_code ec;
    fs::create_directories(parent, ec);
    if (ec) throw_file_error(path, "cannot create its folder {}: {}", parent.string(), ec.message());
    remove_stale_temporaries(path);
}

}  // namespace

fs::path temporary_path(const fs::path& path, long pid) {
    const fs::path parent = path.has_parent_path() ? path.parent_path() : fs::path(".");
    const std::string signature = fmt::format("{}{}-{}-{:016x}", kTemporaryMarker, host_tag(), pid, random_bits());
    // Keep the target's extension last: some writers pick the format from it.
    // A name the file system takes (NAME_MAX) must give a temporary it takes
    // too, so the stem is cut to what the signature leaves.
    std::string extension = path.extension().string();
    if (1 + signature.size() + extension.size() > size_t(NAME_MAX)) extension.clear();  // no format is that long
    const std::string stem = utf8_prefix(path.stem().string(), size_t(NAME_MAX) - 1 - signature.size() - extension.size());
    return parent / ("." + stem + signature + extension);
}

void remove_stale_temporaries(const fs::path& path) {
    const fs::path parent = path.has_parent_path() ? path.parent_path() : fs::path(".");
    const std::string own_host = host_tag();
    const auto now = fs::file_time_type::clock::now();
    std::error_code ec;
    for (fs::directory_iterator it(parent, ec), end; !ec && it != end; it.increment(ec)) {
        const std::optional<TemporaryName> name = parse_temporary(it->path().filename().string());
        if (!name) continue;
        // A live writer (this process's other threads included) may be about
        // to rename its file; only a PID of this host and namespace can be asked.
        bool orphan = name->host == own_host && name->pid > 0 && name->pid != long(::getpid()) &&
                      ::kill(pid_t(name->pid), 0) != 0 && errno == ESRCH;
        std::error_code time_error;
        const auto written = it->last_write_time(time_error);
        orphan = orphan || (!time_error && now - written > kOrphanedTemporaryAge);
        std::error_code remove_error;  // another sweeper may have been first
        if (orphan) fs::remove(it->path(), remove_error);
    }
}

void write_atomically(const fs::path& path, const std::function<void(const fs::path&)>& write) {
    prepare_folder(path);
    Temporary tmp(path);
    tmp.close();  // write() opens it by name
    write(tmp.path());
    tmp.install();
}

void write_file_atomically(const fs::path& path, std::string_view contents) {
    prepare_folder(path);
    Temporary tmp(path);
    tmp.write(contents);
    tmp.close();
    tmp.install();
}

namespace {

// A file's device and inode where it exists (links and hard links are one
// file), and its absolute spelling with links and "x/.." resolved, which is
// what a write to a path that does not exist yet creates ("new/../in.exr"
// has no inode until its folder is made, then replaces in.exr).
struct FileIdentity {
    std::optional<std::pair<uint64_t, uint64_t>> inode;
    std::string name;
};
FileIdentity file_identity(const fs::path& path) {
    FileIdentity identity;
    struct stat status = {};
    if (::stat(path.c_str(), &status) == 0) identity.inode = {uint64_t(status.st_dev), uint64_t(status.st_ino)};
    std::error_code ec;
    identity.name = fs::weakly_canonical(fs::absolute(path, ec), ec).lexically_normal().string();
    return identity;
}

// Files by inode and by name: `rsl render --frames` checks up to 100,000 numbered outputs.
class FileIndex {
public:
    const fs::path* find(const FileIdentity& identity) const {
        if (identity.inode)
            if (const auto hit = inodes_.find(*identity.inode); hit != inodes_.end()) return &hit->second;
        const auto hit = names_.find(identity.name);
        return hit == names_.end() ? nullptr : &hit->second;
    }
    void add(const FileIdentity& identity, const fs::path& path) {
        if (identity.inode) inodes_.emplace(*identity.inode, path);
        names_.emplace(identity.name, path);
    }

private:
    std::map<std::pair<uint64_t, uint64_t>, fs::path> inodes_;
    std::map<std::string, fs::path> names_;
};

}  // namespace

void check_outputs_apart(const std::vector<fs::path>& outputs, const std::vector<fs::path>& inputs) {
    FileIndex read, written;
    for (const fs::path& input : inputs)
        if (!input.empty()) read.add(file_identity(input), input);
    for (const fs::path& output : outputs) {
        if (output.empty()) continue;
        const FileIdentity identity = file_identity(output);
        if (const fs::path* input = read.find(identity))
            throw_file_error(output, "this output is the input {}: writing it would destroy what is read; "
                                     "choose another output path", input->string());
        if (const fs::path* other = written.find(identity))
            throw_file_error(output, "two outputs are this one file ({}): one would overwrite the other; "
                                     "give them different paths", other->string());
        written.add(identity, output);
    }
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
