// SPDX-License-Identifier: MIT
#include "core/thread_environment.h"

#include <fmt/format.h>
#include <omp.h>

#include <charconv>
#include <cstdlib>
#include <string_view>

#include "core/error.h"

namespace sabo {

std::string check_thread_environment() {
    const char* value = std::getenv("OMP_NUM_THREADS");
    if (value == nullptr) return {};
    const std::string_view text(value);
    const std::string_view first = text.substr(0, text.find(','));
    long threads = 0;
    const auto [end, error] = std::from_chars(first.data(), first.data() + first.size(), threads);
    if (error != std::errc() || end != first.data() + first.size() || threads < 1 || threads > max_threads)
        throw InputError(
            fmt::format("OMP_NUM_THREADS={}: the threads must be a whole number from 1 to {} (as "
                        "--threads); unset it to use every core",
                        text, max_threads));
    const int cores = omp_get_num_procs();
    if (threads > cores)
        return fmt::format(
            "OMP_NUM_THREADS={} asks for more threads than this machine's {} cores: they take "
            "turns (slower, not wrong)",
            threads, cores);
    return {};
}

}  // namespace sabo
