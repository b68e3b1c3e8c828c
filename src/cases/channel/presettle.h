// SPDX-License-Identifier: MIT
// "Highly-compacted" preparation of a release (reference case C4).
#pragma once
#include "cases/channel/channel_settings.h"
#include "dem/particles.h"
#include "sim/run_control.h"

namespace sabo::cases {

// "Highly-compacted" preparation: the block is discharged against a temporary closed barrier just in
// front of it (a plane 5 mm ahead of the block front) and left to settle — until the complete-stop
// criterion holds or release.settle_max_time_s — then that barrier is removed and the run starts (t = 0)
// from the settled state at rest. A stop request (Ctrl-C) ends the settling early; the run that follows
// then stops at once.
[[nodiscard]] dem::Particles presettle(const PreparedCase& pc, sim::RunControl& control);

}  // namespace sabo::cases
