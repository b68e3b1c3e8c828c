// SPDX-License-Identifier: MIT
#include "scenario/csv_table.h"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "core/error.h"

namespace sabo::scenario {

namespace {

std::vector<std::string> split_csv(const std::string& line) {
    std::vector<std::string> out;
    std::stringstream in(line);
    std::string cell;
    while (std::getline(in, cell, ',')) {
        const auto first = cell.find_first_not_of(" \t\r");
        const auto last = cell.find_last_not_of(" \t\r");
        out.push_back(first == std::string::npos ? std::string() : cell.substr(first, last - first + 1));
    }
    return out;
}

}  // namespace

CsvTable read_csv_table(const std::filesystem::path& file, std::string_view what, std::size_t max_rows) {
    // a regular file of bounded size: a device or a pipe named here (/dev/zero) must not hang the reader
    std::error_code error;
    if (!std::filesystem::is_regular_file(file, error))
        throw InputError(fmt::format("{}: cannot read {}: not a regular file", file.string(), what));
    if (std::filesystem::file_size(file, error) > (std::uintmax_t{1} << 30))
        throw InputError(fmt::format("{}: larger than 1 GiB ({})", file.string(), what));
    std::ifstream in(file);
    if (!in) throw InputError(fmt::format("{}: cannot read {}", file.string(), what));
    CsvTable table;
    std::string line;
    if (!std::getline(in, line))
        throw InputError(fmt::format("{}: empty (a header is expected; {})", file.string(), what));
    table.header = split_csv(line);
    for (std::size_t number = 2; std::getline(in, line); ++number) {
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        const std::vector<std::string> cells = split_csv(line);
        if (cells.size() != table.header.size())
            throw InputError(fmt::format("{}: line {}: {} values, the header names {}", file.string(), number,
                                         cells.size(), table.header.size()));
        std::vector<double> row(cells.size());
        for (std::size_t k = 0; k < cells.size(); ++k) {
            std::size_t used = 0;
            try {
                row[k] = std::stod(cells[k], &used);
            } catch (const std::exception&) {
                used = 0;
            }
            if (used != cells[k].size() || cells[k].empty() || !std::isfinite(row[k]))
                throw InputError(fmt::format("{}: line {}: {} = '{}' is not a finite number", file.string(),
                                             number, table.header[k], cells[k]));
        }
        table.rows.push_back(std::move(row));
        table.lines.push_back(number);
        if (table.rows.size() > max_rows)
            throw InputError(fmt::format("{}: more than {} rows ({})", file.string(), max_rows, what));
    }
    return table;
}

std::filesystem::path beside_case(const std::filesystem::path& case_file,
                                  const std::filesystem::path& named) {
    return named.is_absolute() ? named : case_file.parent_path() / named;
}

}  // namespace sabo::scenario
