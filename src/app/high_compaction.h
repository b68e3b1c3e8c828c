// SPDX-License-Identifier: MIT
// "Highly-compacted" preparation of a release (CASES C4).
#pragma once
#include "app/case_setup.h"
#include "dem/particles.h"

namespace sabo::app {

// "Highly-compacted" preparation (CASES C4): the block is discharged against a temporary closed
// barrier just in front of it (a plane 5 mm ahead of the block front) and left to settle — until the
// complete-stop criterion holds or release.settle_max_time_s — then that barrier is removed and the
// run starts (t = 0) from the settled state at rest.
[[nodiscard]] dem::Particles presettle(const PreparedCase& pc);

}  // namespace sabo::app
