// SPDX-License-Identifier: MIT
// How OpenMP's idle threads wait (docs/scaling.md, "Threads on a shared machine"). libgomp's threads spin
// for 300 000 iterations at every barrier before they sleep; on a machine whose cores other programs also
// use, those spins take the time slices the working threads need, and a run slows by far more than its
// share of the cores (measured: 4.4× on a 2-core machine running two other busy processes). A shorter spin
// (GOMP_SPINCOUNT=10000) keeps an idle machine's speed and gives a busy one its fair share. libgomp reads
// its settings when it loads, before main(): so the program starts itself again, once, with them set.
#pragma once
#include <string>

namespace sabo {

// Unless the user chose how threads wait (OMP_WAIT_POLICY or GOMP_SPINCOUNT set), sets GOMP_SPINCOUNT to
// `spin_count` and re-executes this program with the same arguments (the same process: a launcher such as
// mpirun sees no change). Returns if the user chose, or if the re-execution fails (the run then goes on
// with libgomp's defaults). Call first in main(), before any thread or MPI exists.
void wait_politely(char** argv, long spin_count = 10000);
// How this process's threads wait, as the environment says ("GOMP_SPINCOUNT=10000", "OMP_WAIT_POLICY=…",
// or "libgomp's default"): for the run's start line.
[[nodiscard]] std::string thread_waiting();

}  // namespace sabo
