// SPDX-License-Identifier: MIT
#include "io/atomic_file.h"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <fstream>

#include "core/error.h"

namespace sabo::io {

void write_atomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& fill) {
    std::filesystem::path tmp = path;
    tmp += ".tmp";
    // a write that fails says why (the system's reason: no space left, file too large, ...) and leaves no
    // partial .tmp behind; the file it was to replace stays as it was
    const auto discard = [&tmp] {
        std::error_code ignored;
        std::filesystem::remove(tmp, ignored);
    };
    const auto fail = [&](const std::string& what, int reason) {
        discard();
        throw RunError(fmt::format("{} {}: {}", what, tmp.string(),
                                   reason != 0 ? std::strerror(reason) : "reason not given by the system"));
    };
    errno = 0;
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) fail("cannot write", errno);
    try {
        fill(out);
    } catch (...) {
        out.close();
        discard();
        throw;
    }
    out.close();  // (flushes: a full disk shows here)
    if (!out) fail("writing failed:", errno);
    std::error_code error;
    std::filesystem::rename(tmp, path, error);
    if (error) fail(fmt::format("cannot rename to {}:", path.string()), error.value());
}

void write_text_atomically(const std::filesystem::path& path, std::string_view text) {
    write_atomically(
        path, [text](std::ostream& os) { os.write(text.data(), static_cast<std::streamsize>(text.size())); });
}

}  // namespace sabo::io
