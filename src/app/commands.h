// SPDX-License-Identifier: MIT
// The `sabo run` and `sabo check` commands. Exit codes: 0 ok, 2 bad input, 3 run failure,
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

int run_case(const CaseRequest& request);
int check_case(const CaseRequest& request);

}  // namespace sabo::app
