#pragma once
// What issue 43 found reading paths that are not files: a FIFO blocks every
// reader forever, a link to /dev/zero never ends, a sparse file claims
// gigabytes in an instant. Each helper makes one in a scratch folder; the
// readers must refuse it at once, naming the path and what it is.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "src/core/error.h"

namespace rsl::test {

// A FIFO (named pipe) at `path`, which nobody will ever write.
inline std::filesystem::path make_fifo(const std::filesystem::path& path) {
    std::filesystem::remove(path);
    RSL_CHECK(::mkfifo(path.c_str(), 0600) == 0);
    return path;
}

// While alive, after `seconds`, opens and closes the FIFO for writing now and
// then: a reader blocked on it (the defect) then sees an empty file and its
// test fails on the message instead of hanging the suite.
class FifoRelease {
public:
    explicit FifoRelease(std::filesystem::path fifo, double seconds = 5)
        : thread_([this, fifo = std::move(fifo), seconds] {
              const auto start = std::chrono::steady_clock::now();
              while (!done_) {
                  std::this_thread::sleep_for(std::chrono::milliseconds(50));
                  if (std::chrono::steady_clock::now() - start < std::chrono::duration<double>(seconds)) continue;
                  const int fd = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);  // fails unless a reader waits
                  if (fd >= 0) ::close(fd);
              }
          }) {}
    ~FifoRelease() {
        done_ = true;
        thread_.join();
    }
    FifoRelease(const FifoRelease&) = delete;
    FifoRelease& operator=(const FifoRelease&) = delete;

private:
    std::atomic<bool> done_{false};
    std::thread thread_;
};

// A symbolic link at `path` to /dev/zero: endless bytes, all NUL.
inline std::filesystem::path make_dev_zero_link(const std::filesystem::path& path) {
    std::filesystem::remove(path);
    std::filesystem::create_symlink("/dev/zero", path);
    return path;
}

// A directory at `path`, named like a file.
inline std::filesystem::path make_directory(const std::filesystem::path& path) {
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
    return path;
}

// A file of `size` bytes that begins with `start` and is a hole after it:
// it takes no disk and is made in an instant.
inline std::filesystem::path make_sparse_file(const std::filesystem::path& path, uintmax_t size,
                                              const std::string& start = "") {
    std::filesystem::remove(path);
    {
        std::ofstream out(path, std::ios::binary);
        out << start;
    }
    std::filesystem::resize_file(path, size);
    return path;
}

}  // namespace rsl::test
