// SPDX-License-Identifier: MIT
// "Highly-compacted" preparation of a release (CASES C4).
#pragma once
#include "dem/particles.h"
#include "sim/case_setup.h"
#include "sim/run_control.h"

namespace sabo::sim {

// "Highly-compacted" preparation: the block is discharged against a temporary closed barrier just in
// front of it (a plane 5 mm ahead of the block front) and left to settle — until the complete-stop
// criterion holds or release.settle_max_time_s — then that barrier is removed and the run starts (t = 0)
// from the settled state at rest. A stop request (Ctrl-C) ends the settling early; the run that follows
// then stops at once.
[[nodiscard]] dem::Particles presettle(const PreparedCase& pc, RunControl& control);

}  // namespace sabo::sim
