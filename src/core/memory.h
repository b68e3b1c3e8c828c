// SPDX-License-Identifier: MIT
// What the machine can give a run: read before anything large is allocated, so that a case too big for
// it is refused with a message instead of exhausting the memory.
#pragma once

namespace sabo {

// MemAvailable of /proc/meminfo, bytes (unbounded where the file cannot be read).
[[nodiscard]] double available_memory_bytes();

// What a lattice divided among ranks may fill: this machine's available memory times the machines an MPI
// launcher spread the ranks over (its ranks over those on this machine, the machines taken to be alike); a
// single process's is this machine's.
[[nodiscard]] double memory_of_all_machines_bytes();

}  // namespace sabo
