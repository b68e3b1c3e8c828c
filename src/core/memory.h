// SPDX-License-Identifier: MIT
// What the machine can give a run: read before anything large is allocated, so that a case too big for
// it is refused with a message instead of exhausting the memory.
#pragma once

namespace sabo {

// MemAvailable of /proc/meminfo, bytes (unbounded where the file cannot be read).
[[nodiscard]] double available_memory_bytes();

}  // namespace sabo
