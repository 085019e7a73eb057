#pragma once
// Tests that need a file system of their own (a tiny full tmpfs) or a PID
// namespace of their own run their body in a forked child that unshares the
// namespace; the body reports back through a pipe. Where the machine refuses
// (no CAP_SYS_ADMIN, no user namespaces), the test is skipped with a WARN that
// says so, never passed silently.
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include <fcntl.h>
#include <sched.h>
#include <sys/mount.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>

namespace rsl::test {

// Runs body() in a forked child; returns what it returned (an empty string
// for success, else what went wrong), or nullopt when `prepare` (run first in
// the child) failed, with its reason in `refused`.
inline std::optional<std::string> in_child(const std::function<std::string()>& prepare,
                                           const std::function<std::string()>& body, std::string& refused) {
    int pipe_fds[2];
    if (::pipe(pipe_fds) != 0) return std::string("pipe failed");
    const pid_t child = ::fork();
    if (child == 0) {
        ::close(pipe_fds[0]);
        std::string text = prepare();
        const bool prepared = text.empty();
        if (prepared) text = body();
        const std::string message = (prepared ? "R" : "P") + text;  // body's result or prepare's refusal
        (void)!::write(pipe_fds[1], message.data(), message.size());
        std::_Exit(0);
    }
    ::close(pipe_fds[1]);
    std::string message;
    char buffer[4096];
    for (ssize_t n; (n = ::read(pipe_fds[0], buffer, sizeof(buffer))) > 0;) message.append(buffer, size_t(n));
    ::close(pipe_fds[0]);
    int status = 0;
    ::waitpid(child, &status, 0);
    if (message.empty()) return fmt::format("the child reported nothing (status {:#x})", status);
    if (message[0] == 'P') {
        refused = message.substr(1);
        return std::nullopt;
    }
    return message.substr(1);
}

// Mounts a tmpfs of `bytes` on `dir` in a mount namespace of this (child)
// process alone; "" on success, else why not.
inline std::string mount_private_tmpfs(const std::filesystem::path& dir, size_t bytes) {
    if (::unshare(CLONE_NEWNS) != 0) return fmt::format("unshare(CLONE_NEWNS): {}", std::strerror(errno));
    // Private propagation: the mount must not show in the parent's namespace.
    if (::mount(nullptr, "/", nullptr, MS_REC | MS_PRIVATE, nullptr) != 0)
        return fmt::format("making / private: {}", std::strerror(errno));
    const std::string options = fmt::format("size={}", bytes);
    if (::mount("tmpfs", dir.c_str(), "tmpfs", 0, options.c_str()) != 0)
        return fmt::format("mount -t tmpfs {}: {}", dir.string(), std::strerror(errno));
    return "";
}

// Fills the file system of `dir` with one file, then shrinks it so that
// about `left` bytes stay free; "" on success.
inline std::string fill_leaving(const std::filesystem::path& dir, size_t left) {
    const std::string filler = (dir / "filler").string();
    const int fd = ::open(filler.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0) return fmt::format("{}: {}", filler, std::strerror(errno));
    const std::string block(4096, 'f');
    off_t size = 0;
    for (ssize_t n; (n = ::write(fd, block.data(), block.size())) > 0;) size += n;
    const int full_errno = errno;
    const bool shrunk = size > off_t(left) && ::ftruncate(fd, size - off_t(left)) == 0;
    ::close(fd);
    if (full_errno != ENOSPC) return fmt::format("filling {} ended with {}", filler, std::strerror(full_errno));
    return shrunk ? "" : "the file system is smaller than the room asked to leave";
}

}  // namespace rsl::test
