// SPDX-License-Identifier: MIT
// The `sabo run`, `sabo check` and `sabo sweep` commands. Exit codes: 0 ok, 2 bad input, 3 run failure,
// 130 interrupted (outputs written up to the interruption).
#pragma once
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace sabo::app {

struct CaseRequest {
    std::filesystem::path case_file;
    std::vector<std::string> overrides;  // "key.path=value"
    std::optional<std::filesystem::path> out_dir;
    int threads = 0;  // 0: OpenMP default
};

struct SweepRequest {
    std::filesystem::path sweep_file;
    std::optional<std::filesystem::path> out_dir;
    int jobs = 0;  // 0: the sweep file's
};

int run_case(const CaseRequest& request);
// Exit codes: 0 all cases completed, 2 bad sweep file, 3 some case failed, 130 interrupted.
int run_sweep(const SweepRequest& request);
int check_case(const CaseRequest& request);

}  // namespace sabo::app
