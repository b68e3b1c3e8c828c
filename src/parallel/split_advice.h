// SPDX-License-Identifier: MIT
// How to spread one run over a machine's cores, or over several machines (docs/scaling.md, "Threads or
// ranks"): on one machine the OpenMP threads of one process, because they share the lattice and step every
// cell once, where ranks step ghost planes twice and copy them every step (measured on 2 cores: 2 ranks ×
// 1 thread at 0.81–0.89 of 1 process × 2 threads on coupled runs); ranks (slabs, `mpirun`) when the run
// needs more memory than one machine has, one rank per machine with as many threads as it has cores.
#pragma once
#include <string>

namespace sabo::parallel {

struct SplitAdvice {
    int machines = 1;  // ranks, one per machine
    int threads = 1;   // per rank
    std::string text;  // one line for `sabo check`
};

// `run_bytes`: the run's memory estimate, `lattice_bytes` the lattice's part of it; `cores` and
// `available_bytes`: this machine's (the machines a divided run would use are taken to be like it). A rank
// may use 80 % of its machine's available memory; a divided run's rank also keeps a second lattice of its
// slab (up to a quarter larger) in which the faces' next move builds the new one.
[[nodiscard]] SplitAdvice advise_split(double run_bytes, double lattice_bytes, int cores,
                                       double available_bytes);

}  // namespace sabo::parallel
