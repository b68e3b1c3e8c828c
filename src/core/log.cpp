// SPDX-License-Identifier: MIT
#include "core/log.h"

#include <fmt/format.h>
#include <spdlog/sinks/basic_file_sink.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <string>

namespace sabo {

void init_logging(bool verbose, std::string_view process) {
    auto logger = spdlog::stderr_color_mt("sabo");
    logger->set_pattern(process.empty() ? std::string("%^[%l]%$ %v")
                                        : fmt::format("%^[%l]%$ [{}] %v", process));
    logger->set_level(verbose ? spdlog::level::debug : spdlog::level::info);
    spdlog::set_default_logger(logger);
}

void add_log_file(const std::filesystem::path& path, bool append) {
    auto sink = std::make_shared<spdlog::sinks::basic_file_sink_mt>(path.string(), !append);
    sink->set_pattern("[%Y-%m-%d %H:%M:%S.%e] [%l] %v");
    spdlog::default_logger()->sinks().push_back(sink);
    spdlog::default_logger()->flush_on(spdlog::level::info);
}

}  // namespace sabo
