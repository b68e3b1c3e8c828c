// SPDX-License-Identifier: MIT
#include "io/folder_lock.h"

#include <fcntl.h>
#include <fmt/chrono.h>
#include <fmt/format.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <mutex>
#include <set>
#include <string>

#include "core/error.h"

namespace sabo::io {

void lock_run_folder(const std::filesystem::path& dir) {
    static std::mutex guard;
    static std::set<std::filesystem::path> held;  // (their descriptors stay open until the process ends)
    std::error_code error;
    const std::filesystem::path real = std::filesystem::weakly_canonical(dir, error);
    const std::filesystem::path key = error ? dir : real;
    const std::lock_guard<std::mutex> lock(guard);
    if (held.contains(key)) return;
    // a folder reached through a link is named as such: the holder may have named the other path
    std::string given = dir.string();
    while (given.size() > 1 && given.back() == '/') given.pop_back();
    const std::string named = std::filesystem::is_symlink(given, error)
                                  ? fmt::format("{} (a link to {})", dir.string(), key.string())
                                  : dir.string();
    const std::filesystem::path file = dir / ".sabo.lock";
    const int fd = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0)
        throw InputError(fmt::format("{}: cannot open its lock file: {}", named, std::strerror(errno)));
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
        const int why = errno;
        char holder[256] = {};
        const ssize_t n = ::pread(fd, holder, sizeof holder - 1, 0);
        ::close(fd);
        std::string who = n > 0 ? std::string(holder, static_cast<std::size_t>(n)) : std::string("unknown");
        while (!who.empty() && (who.back() == '\n' || who.back() == ' ')) who.pop_back();
        if (why == EWOULDBLOCK)
            throw InputError(
                fmt::format("the output folder {} is in use by another run ({}): wait for it to "
                            "end, or choose another folder (--out)",
                            named, who));
        throw InputError(fmt::format("{}: cannot lock its lock file: {}", named, std::strerror(why)));
    }
    const std::string me =
        fmt::format("process {}, since {:%Y-%m-%d %H:%M:%S} UTC\n", ::getpid(),
                    std::chrono::floor<std::chrono::seconds>(std::chrono::system_clock::now()));
    if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, me.data(), me.size(), 0) != static_cast<ssize_t>(me.size()))
        throw InputError(fmt::format("{}: cannot write its lock file: {}", named, std::strerror(errno)));
    held.insert(key);
}

}  // namespace sabo::io
