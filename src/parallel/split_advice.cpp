// SPDX-License-Identifier: MIT
#include "parallel/split_advice.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace sabo::parallel {

SplitAdvice advise_split(double run_bytes, double lattice_bytes, int cores, double available_bytes) {
    constexpr double usable = 0.8;
    constexpr double mib = 1048576.0;
    SplitAdvice a;
    a.threads = std::max(1, cores);
    const double per_machine = usable * available_bytes;
    if (!(run_bytes > per_machine) || !std::isfinite(available_bytes)) {
        a.text = fmt::format(
            "threads or ranks: one process with --threads {} (this machine's cores; the default): the run's "
            "{:.0f} MiB fit its memory, and on one machine threads beat MPI ranks (ranks step and copy ghost "
            "planes every step: docs/scaling.md)",
            a.threads, run_bytes / mib);
        return a;
    }
    a.machines = static_cast<int>(std::ceil((run_bytes + 1.25 * lattice_bytes) / per_machine));
    a.text = fmt::format(
        "threads or ranks: the run's {:.0f} MiB exceed 80 % of this machine's available memory ({:.0f} MiB): "
        "divide it among {} machines like this one, one rank each with --threads {} (mpirun -np {} --map-by "
        "node sabo run …; docs/distributed.md)",
        run_bytes / mib, available_bytes / mib, a.machines, a.threads, a.machines);
    return a;
}

}  // namespace sabo::parallel
