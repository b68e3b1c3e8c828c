// SPDX-License-Identifier: MIT
// A table of numbers from a CSV file a case names (grains to place, a hydrograph): a header line of column
// names, then one row of finite numbers per line (blank lines skipped). Every refusal names the file, what it
// is (with the case key that named it) and the line.
#pragma once
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace sabo::scenario {

struct CsvTable {
    std::vector<std::string> header;
    std::vector<std::vector<double>> rows;  // each as long as the header
    std::vector<std::size_t> lines;         // the file's line of each row (1: the header)
};

// Reads `file` (a regular file of at most 1 GiB; at most `max_rows` rows); `what` names it in messages
// ("the grains' file (grains.file)").
[[nodiscard]] CsvTable read_csv_table(const std::filesystem::path& file, std::string_view what,
                                      std::size_t max_rows);

// The file a case key names: as given when absolute, else relative to the case file `case_file`.
[[nodiscard]] std::filesystem::path beside_case(const std::filesystem::path& case_file,
                                                const std::filesystem::path& named);

}  // namespace sabo::scenario
