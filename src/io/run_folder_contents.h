// SPDX-License-Identifier: MIT
// What a run leaves in its output folder, so that a new run does not mix its files with an earlier run's
// (a shorter run left the earlier run's frames beside a .pvd that lists only its own).
#pragma once
#include <filesystem>

namespace sabo::io {

// Whether `dir` holds the outputs of a run that ended (summary.json) or can be resumed (checkpoint.bin). A
// run stopped before its first checkpoint leaves neither: nothing can continue its partial outputs.
[[nodiscard]] bool holds_run_outputs(const std::filesystem::path& dir);

// Removes from `dir` the files a run writes there (the named outputs, the top-level .pvd/.vtp/.vti/.vtu/.png
// files, their .tmp, the frames/ folder and python/view.py's views/) and nothing else: a user's own files in
// the folder stay. Returns how many it removed (a folder counts once).
int clear_run_outputs(const std::filesystem::path& dir);

}  // namespace sabo::io
