// SPDX-License-Identifier: MIT
// Write-then-rename: a reader (or an interrupted run) never sees a half-written file.
#pragma once
#include <filesystem>
#include <functional>
#include <ostream>
#include <string_view>

namespace sabo::io {

// Calls `fill` on a stream to <path>.tmp, flushes, then renames it over `path`. Throws on failure.
void write_atomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& fill);
void write_text_atomically(const std::filesystem::path& path, std::string_view text);

}  // namespace sabo::io
