// SPDX-License-Identifier: MIT
#include "io/atomic_file.h"

#include <fmt/format.h>

#include <fstream>
#include <stdexcept>

namespace sabo::io {

void write_atomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& fill) {
    std::filesystem::path tmp = path;
    tmp += ".tmp";
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        if (!out) throw std::runtime_error(fmt::format("cannot write {}", tmp.string()));
        fill(out);
        out.flush();
        if (!out) throw std::runtime_error(fmt::format("write failed: {}", tmp.string()));
    }
    std::filesystem::rename(tmp, path);
}

void write_text_atomically(const std::filesystem::path& path, std::string_view text) {
    write_atomically(
        path, [text](std::ostream& os) { os.write(text.data(), static_cast<std::streamsize>(text.size())); });
}

}  // namespace sabo::io
