// SPDX-License-Identifier: MIT
// End-of-run barrier outputs (docs/outputs.md): local force maps at t1, t2, t3 and the end and the
// envelope, as .vtp (one point per barrier element) and together in barrier_maps.csv; the arching
// intervals of every outlet in arching.csv; a mixture's deposit composition.
#pragma once
#include <filesystem>

#include "analysis/arching.h"
#include "analysis/barrier_forces.h"
#include "dem/particles.h"
#include "io/json_writer.h"
#include "scenario/barrier.h"
#include "scenario/channel_case.h"

namespace sabo::io {

void write_force_maps(const std::filesystem::path& dir, const scenario::BarrierInfo& barrier,
                      const analysis::BarrierForceMonitor& forces);
void write_arching(const std::filesystem::path& dir, const analysis::ArchingMonitor& arching, double t0);
// Mixtures: volume fraction of large grains in slabs of the deposit (deposit_composition.csv).
void write_deposit_composition(const std::filesystem::path& dir, const scenario::ChannelCase& scene,
                               const dem::Particles& p);
// summary.json's barrier_face_x_m and barrier_face_normal: where the face is and the direction the force
// maps' normal component is taken along (the report's pressures over the barrier's height).
void add_barrier_face(JsonObject& js, const scenario::BarrierInfo& barrier);

}  // namespace sabo::io
