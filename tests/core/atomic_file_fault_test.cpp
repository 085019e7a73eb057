// Issue 43: every atomic write checks its writes and its close (a full disk is
// refused, naming the target and the reason); temporaries are unique across
// PID namespaces; an error carries its real reason; orphaned temporaries are
// swept and SIGINT/SIGTERM remove a process's own.
#include <atomic>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <random>
#include <thread>

#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>

#include "src/core/atomic_file.h"
#include "src/core/error.h"
#include "src/formats/image_file.h"
#include "tests/interrupted_run.h"
#include "tests/private_mounts.h"
#include "tests/test_support.h"

using namespace rsl;
using namespace rsl::test;
namespace fs = std::filesystem;

namespace {

bool contains(const std::string& text, const std::string& fragment) { return text.find(fragment) != std::string::npos; }

// Noise does not compress: its PNG and EXR are about as large as its pixels.
Image noise_image(int width, int height) {
    Image image(width, height);
    std::mt19937 random(43);
    std::uniform_real_distribution<float> value(0.0f, 1.0f);
    for (float& v : image.pixels) v = value(random);
    return image;
}

// What a writer that must fail on the full disk did wrong; "" when it refused
// properly: an rsl::Error naming the target and ENOSPC's reason, the earlier
// file untouched, no temporary left.
std::string check_refused(const fs::path& target, const std::function<void()>& write) {
    std::string problems;
    const std::string message = error_of(write);
    if (message.empty()) problems += "no error; ";
    if (!contains(message, target.string())) problems += "the message does not name the target; ";
    if (!contains(message, "No space left on device")) problems += "the message does not give the reason; ";
    if (read_bytes(target) != "earlier") problems += "the earlier file was replaced; ";
    for (const fs::path& left : temporaries_in(target.parent_path())) problems += "left " + left.string() + "; ";
    return problems.empty() ? "" : message + ": " + problems;
}

}  // namespace

TEST_CASE("a full disk: every writer refuses, naming the target and the reason, and keeps the earlier file",
          "[atomic-file][full-disk]") {
    const fs::path dir = scratch_dir("atomic_full");
    std::string refused;
    const auto result = in_child([&] { return mount_private_tmpfs(dir, 1 << 20); }, [&]() -> std::string {
        const Image image = noise_image(256, 256);  // 196 KB as PNG, 786 KB as float EXR
        const std::vector<fs::path> targets = {dir / "a.png", dir / "a.exr", dir / "a.rslf"};
        for (const fs::path& target : targets) write_text(target, "earlier");
        if (const std::string full = fill_leaving(dir, 64 << 10); !full.empty()) return full;
        std::string problems;
        problems += check_refused(targets[0], [&] { write_png(targets[0], image); });
        problems += check_refused(targets[1], [&] { write_exr(targets[1], image); });
        problems += check_refused(targets[2], [&] { write_file_atomically(targets[2], std::string(200 << 10, 'x')); });
        return problems;
    }, refused);
    if (!result) {
        WARN("SKIPPED: cannot mount a small tmpfs here (" << refused << "); the full-disk test did not run");
        return;
    }
    CHECK(*result == "");
}

TEST_CASE("a target that is a directory: the error names it and gives the real reason", "[atomic-file]") {
    const fs::path dir = scratch_dir("atomic_directory");
    const fs::path target = dir / "svdf-0.rslf";
    fs::create_directories(target / "inside");
    const std::string message = error_of([&] { write_file_atomically(target, "field"); });
    INFO(message);
    CHECK(contains(message, target.string()));
    CHECK(contains(message, "Is a directory"));
    CHECK(!contains(message, "Success"));
    CHECK(!contains(message, "does not exist"));
    CHECK(temporaries_in(dir).empty());
}

TEST_CASE("two writers that are both PID 1 (separate PID namespaces) write one target at once",
          "[atomic-file][pid-namespace]") {
    const fs::path dir = scratch_dir("atomic_pid_namespaces");
    const fs::path target = dir / "svdf-0.rslf";
    // Each writer holds its temporary open until both exist (or 3 s pass), so
    // that the two writes overlap for certain.
    const auto writer = [&](char fill) {
        return [&, fill]() -> std::string {
            int report[2];
            if (::pipe(report) != 0) return "pipe failed";
            const pid_t child = ::fork();  // PID 1 of the new namespace
            if (child == 0) {
                std::string message = ::getpid() == 1 ? "" : "not PID 1";
                if (message.empty())
                    message = error_of([&] {
                        write_atomically(target, [&](const fs::path& tmp) {
                            write_text(tmp, std::string(1 << 16, fill));
                            for (int wait = 0; wait < 3000 && temporaries_in(dir).size() < 2; ++wait) ::usleep(1000);
                        });
                    });
                (void)!::write(report[1], message.data(), message.size());
                std::_Exit(0);
            }
            ::close(report[1]);
            std::string message;
            char buffer[1024];
            for (ssize_t n; (n = ::read(report[0], buffer, sizeof(buffer))) > 0;) message.append(buffer, size_t(n));
            ::waitpid(child, nullptr, 0);
            return message;
        };
    };
    const auto new_pid_namespace = []() -> std::string {
        return ::unshare(CLONE_NEWPID) == 0 ? "" : fmt::format("unshare(CLONE_NEWPID): {}", std::strerror(errno));
    };
    std::optional<std::string> a, b;
    std::string refused_a, refused_b;
    std::thread first([&] { a = in_child(new_pid_namespace, writer('a'), refused_a); });
    std::thread second([&] { b = in_child(new_pid_namespace, writer('b'), refused_b); });
    first.join(), second.join();
    if (!a || !b) {
        WARN("SKIPPED: no PID namespace here (" << refused_a << refused_b << "); the collision test did not run");
        return;
    }
    CHECK(*a == "");
    CHECK(*b == "");
    const std::string written = read_bytes(target);
    CHECK((written == std::string(1 << 16, 'a') || written == std::string(1 << 16, 'b')));
    CHECK(temporaries_in(dir).empty());
}

TEST_CASE("temporary names differ between writes and carry this host and process", "[atomic-file]") {
    const fs::path target = "cache/svdf-0.rslf";
    const fs::path one = temporary_path(target, 1), two = temporary_path(target, 1);
    CHECK(one != two);
    CHECK(one.parent_path() == "cache");
    CHECK(one.extension() == ".rslf");
    CHECK(one.filename().string().rfind(".svdf-0.rsl-tmp-", 0) == 0);
    CHECK(contains(one.filename().string(), "-1-"));
}

TEST_CASE("a file name the file system takes gets a temporary it takes too, the extension kept", "[atomic-file]") {
    const fs::path dir = scratch_dir("atomic_long_name");
    for (const size_t length : {size_t(200), size_t(240), size_t(255)}) {
        const fs::path target = dir / (std::string(length - 4, 'n') + ".exr");
        INFO(length << " bytes");
        CHECK(temporary_path(target, 4194304).filename().string().size() <= 255);
        CHECK(temporary_path(target, 1).extension() == ".exr");
        write_file_atomically(target, "whole");
        CHECK(read_bytes(target) == "whole");
    }
    // A multi-byte character is never cut in half.
    std::string accented;
    for (int i = 0; i < 120; ++i) accented += "\xc3\xa9";  // é, 240 bytes
    const std::string cut = temporary_path(dir / (accented + ".exr"), 1).filename().string();
    CHECK(cut.size() <= 255);
    const size_t stem_end = cut.find(".rsl-tmp-");
    REQUIRE(stem_end != std::string::npos);
    CHECK((stem_end - 1) % 2 == 0);  // whole two-byte characters after the leading dot
    write_file_atomically(dir / (accented + ".exr"), "whole");
    CHECK(read_bytes(dir / (accented + ".exr")) == "whole");
}

TEST_CASE("a write sweeps the folder's orphaned temporaries: dead local writers', and old ones of other hosts",
          "[atomic-file][sweep]") {
    const fs::path dir = scratch_dir("atomic_sweep");
    const auto plant = [&](const fs::path& name, std::chrono::hours age) {
        write_text(dir / name, "half written");
        fs::last_write_time(dir / name, fs::file_time_type::clock::now() - age);
        return dir / name;
    };
    // Of other targets in the folder: nobody may ever write those again.
    const fs::path dead = plant_stale_temporary(dir / "other.rslf");
    const fs::path live = temporary_path(dir / "other.rslf", 1).filename();  // PID 1 runs
    plant(live, std::chrono::hours(0));
    const fs::path foreign_new = plant(".other.rsl-tmp-0123456789abcdef-4242-fedcba9876543210.rslf", std::chrono::hours(1));
    const fs::path foreign_old = plant(".other.rsl-tmp-0123456789abcdef-4343-fedcba9876543210.rslf", std::chrono::hours(25));
    write_file_atomically(dir / "svdf-0.rslf", "field");
    CHECK(!fs::exists(dead));
    CHECK(fs::exists(dir / live));
    CHECK(fs::exists(foreign_new));
    CHECK(!fs::exists(foreign_old));
}

TEST_CASE("the sweep leaves a user's files alone, however old and however like a temporary they look",
          "[atomic-file][sweep]") {
    const fs::path dir = scratch_dir("atomic_sweep_users_files");
    const auto plant = [&](const fs::path& name) {
        write_text(dir / name, "the user's");
        fs::last_write_time(dir / name, fs::file_time_type::clock::now() - std::chrono::hours(1000));
        return dir / name;
    };
    const std::vector<fs::path> users = {
        plant(".notes.tmp-2024-06.txt"), plant(".other.tmp-4444-0.rslf"), plant(".other.tmp-notes.txt"),
        plant(".x.rsl-tmp-notes.txt"), plant(".x.rsl-tmp-0123456789abcdef-42.txt"),
        plant(".x.rsl-tmp-0123456789ABCDEF-42-fedcba9876543210.txt"),
        plant(".x.rsl-tmp-0123456789abcdef-42-fedcba9876543210-1.txt"), plant("x.rsl-tmp-0123456789abcdef-42-fedcba9876543210")};
    const fs::path orphan = plant(".notes.rsl-tmp-0123456789abcdef-4343-fedcba9876543210.txt");
    write_file_atomically(dir / "notes.txt", "new");
    for (const fs::path& user : users) CHECK(fs::exists(user));
    CHECK(!fs::exists(orphan));  // rsl's own, a day old: swept
    CHECK(read_bytes(dir / "notes.txt") == "new");
}

TEST_CASE("SIGINT or SIGTERM in the middle of a write leaves no temporary", "[atomic-file][signal]") {
    for (const int signal : {SIGINT, SIGTERM}) {
        const fs::path dir = scratch_dir(fmt::format("atomic_signal_{}", signal));
        int ready[2];
        REQUIRE(::pipe(ready) == 0);
        const pid_t child = ::fork();
        REQUIRE(child >= 0);
        if (child == 0) {
            // As in a program that leaves the signals alone (Catch2 catches them).
            std::signal(SIGINT, SIG_DFL), std::signal(SIGTERM, SIG_DFL);
            write_atomically(dir / "image.exr", [&](const fs::path& tmp) {
                write_text(tmp, std::string(1 << 16, 'a'));
                (void)!::write(ready[1], "r", 1);
                for (;;) ::pause();  // interrupted here
            });
            std::_Exit(0);
        }
        char byte = 0;
        REQUIRE(::read(ready[0], &byte, 1) == 1);
        ::close(ready[0]), ::close(ready[1]);
        CHECK(temporaries_in(dir).size() == 1);
        ::kill(child, signal);
        int status = 0;
        ::waitpid(child, &status, 0);
        INFO("signal " << signal);
        CHECK(WIFSIGNALED(status));
        CHECK((WIFSIGNALED(status) && WTERMSIG(status) == signal));  // re-raised: the parent sees the real cause
        for (const fs::path& left : temporaries_in(dir)) FAIL_CHECK("left behind: " << left.filename().string());
        CHECK(!fs::exists(dir / "image.exr"));
    }
}
