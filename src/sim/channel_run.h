// SPDX-License-Identifier: MIT
// `sabo run` for channel cases (CASES C2–C4): the grains released against the barrier, the barrier
// analyses computed during the run (sim/channel_observer.h), stop detection, and the outputs of
// docs/outputs.md.
#pragma once
#include "core/config.h"
#include "sim/case_setup.h"

namespace sabo::sim {

// Exit codes: 0 end time or complete stop, 3 the run failed, 130 interrupted.
int run_channel(const RunRequest& req, const Config& cfg);

}  // namespace sabo::sim
