// SPDX-License-Identifier: MIT
// The thread count the environment asks for (OMP_NUM_THREADS), held to the same limits as --threads: an
// unreadable or out-of-range value would otherwise reach OpenMP, which crashed at 100 000 threads and hung
// at 10 000-30 000.
#pragma once
#include <string>

namespace sabo {

// The most threads a run may ask for (--threads and OMP_NUM_THREADS).
inline constexpr int max_threads = 1024;

// Checks OMP_NUM_THREADS when it is set: its first value (a nested list's outer level) must be a whole number
// from 1 to max_threads, else InputError naming the variable. Returns a warning when it asks for more
// threads than this machine has cores (they take turns: slower, not wrong), else "".
[[nodiscard]] std::string check_thread_environment();

}  // namespace sabo
