// SPDX-License-Identifier: MIT
// Logging set-up: messages go to stderr and, during a run, to <out>/sabo.log as well.
#pragma once
#include <filesystem>
#include <string_view>

namespace sabo {

// `process`: a name put before every console message (one rank of several), or empty.
void init_logging(bool verbose, std::string_view process = {});
// Adds a file sink (truncating) to the default logger.
void add_log_file(const std::filesystem::path& path, bool append = false);

}  // namespace sabo
