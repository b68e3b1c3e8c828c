// SPDX-License-Identifier: MIT
#include "io/run_folder_contents.h"

#include <fmt/format.h>

#include <array>
#include <string_view>
#include <vector>

#include "core/error.h"

namespace sabo::io {

namespace {

// Every file name a run of any case type writes (the writers in src/io, src/sim and src/cases).
constexpr std::array named_outputs{"arching.csv",
                                   "barrier_fluid_elements.csv",
                                   "barrier_maps.csv",
                                   "barrier_piles.csv",
                                   "case_resolved.toml",
                                   "checkpoint.bin",
                                   "deposit_composition.csv",
                                   "design_comparison.csv",
                                   "final_grains.csv",
                                   "gauge.csv",
                                   "grains_series.csv",
                                   "heap.csv",
                                   "inflow.csv",
                                   "inflow_grains.csv",
                                   "report.md",
                                   "resume.toml",
                                   "sabo.log",
                                   "series.csv",
                                   "summary.json"};
constexpr std::array output_extensions{".pvd", ".vtp", ".vti", ".vtu", ".png"};
constexpr std::array markers{"summary.json", "checkpoint.bin"};

bool is_run_output(const std::filesystem::path& name) {
    std::filesystem::path file = name;
    if (file.extension() == ".tmp") file = file.stem();  // a write cut short
    for (const std::string_view n : named_outputs)
        if (file == n) return true;
    for (const std::string_view e : output_extensions)
        if (file.extension() == e) return true;
    return false;
}

}  // namespace

bool holds_run_outputs(const std::filesystem::path& dir) {
    std::error_code error;
    for (const std::string_view m : markers)
        if (std::filesystem::exists(dir / m, error)) return true;
    return false;
}

int clear_run_outputs(const std::filesystem::path& dir) {
    std::error_code error;
    std::vector<std::filesystem::path> doomed;  // (listed first, removed after)
    std::filesystem::directory_iterator it(dir, error);
    if (error) throw RunError(fmt::format("cannot list {}: {}", dir.string(), error.message()));
    for (const auto& entry : it) {
        const std::filesystem::path name = entry.path().filename();
        if (entry.is_symlink(error)) continue;  // (a link is the user's: left, and what it leads to)
        if (((name == "frames" || name == "views") && entry.is_directory(error)) ||
            (entry.is_regular_file(error) && is_run_output(name)))
            doomed.push_back(entry.path());
    }
    for (const auto& path : doomed) {
        std::filesystem::remove_all(path, error);  // a file or a folder
        if (error)
            throw RunError(
                fmt::format("cannot remove the earlier run's {}: {}", path.string(), error.message()));
    }
    return static_cast<int>(doomed.size());
}

}  // namespace sabo::io
