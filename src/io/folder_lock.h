// SPDX-License-Identifier: MIT
// One run at a time in a run folder: two runs (or a run and a resume) writing one folder at once mixed
// their series, summaries and checkpoints, and one of them failed on the other's temporary files.
#pragma once
#include <filesystem>

namespace sabo::io {

// Takes OUTDIR/.sabo.lock (an advisory lock the system drops when this process ends, killed or not) and holds
// it for the rest of this process; the file names the holder (process id, since when). Throws InputError
// naming the holder when another process holds it. Taking a folder this process holds already is a no-op.
void lock_run_folder(const std::filesystem::path& dir);

}  // namespace sabo::io
