// SPDX-License-Identifier: MIT
// The design comparison's files (docs/outputs.md): the run's measurements as the "design_inputs" object
// of summary.json (and read back from it by `sabo design compare`), design_comparison.csv and the table
// `sabo design` prints.
#pragma once
#include <filesystem>
#include <string>

#include "analysis/design/run_comparison.h"
#include "io/json_writer.h"

namespace sabo::io {

[[nodiscard]] JsonObject design_inputs_json(const analysis::design::MeasuredRun& run);
// Reads OUT_DIR/summary.json's "design_inputs"; InputError naming the file and the key when it is missing
// or not a number (a run of another case type, or of a version before the design comparison).
[[nodiscard]] analysis::design::MeasuredRun read_design_inputs(const std::filesystem::path& summary_json);

// design_comparison.csv: every prediction and back-calculated coefficient, one per row (atomically).
void write_design_comparison(const std::filesystem::path& out_dir, const analysis::design::Comparison& c);
// The comparison as a text table; `with_simulated`: the simulated column (false for `sabo design`'s own
// flow).
[[nodiscard]] std::string design_table(const analysis::design::Comparison& c, bool with_simulated);

}  // namespace sabo::io
