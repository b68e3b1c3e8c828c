// SPDX-License-Identifier: MIT
// End-of-run barrier outputs (docs/outputs.md): local force maps at t1, t2, t3 and the end and the
// envelope, as .vtp (one point per barrier element) and together in barrier_maps.csv; the arching
// intervals of every outlet in arching.csv.
#pragma once
#include <filesystem>

#include "analysis/arching.h"
#include "analysis/barrier_forces.h"
#include "scenario/barrier.h"

namespace sabo::io {

void write_force_maps(const std::filesystem::path& dir, const scenario::BarrierInfo& barrier,
                      const analysis::BarrierForceMonitor& forces);
void write_arching(const std::filesystem::path& dir, const analysis::ArchingMonitor& arching, double t0);

}  // namespace sabo::io
