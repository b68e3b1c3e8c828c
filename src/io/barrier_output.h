// SPDX-License-Identifier: MIT
// End-of-run barrier outputs (docs/outputs.md): local force maps at t1, t2, t3 and the end and the
// envelope, as .vtp (one point per barrier element) and together in barrier_maps.csv; the arching
// intervals of every outlet in arching.csv; a mixture's deposit composition.
#pragma once
#include <filesystem>

#include "analysis/arching.h"
#include "analysis/barrier_forces.h"
#include "analysis/facet_maps.h"
#include "dem/particles.h"
#include "geometry/triangle_mesh.h"
#include "io/json_writer.h"
#include "scenario/barrier.h"
#include "scenario/channel_case.h"

namespace sabo::io {

void write_force_maps(const std::filesystem::path& dir, const scenario::BarrierInfo& barrier,
                      const analysis::BarrierForceMonitor& forces);
// barrier_facets.vtp: a mesh barrier's triangles (in the frames' coordinates) with, as cell data, their part
// and area (m²) and at each map's time (t1, t2, t3, end; grains_peak: the grains' largest normal force;
// fluid_peak: the fluid's) the grains' contact force on each triangle (grain_force_<map>_N) and the fluid's
// (fluid_force_<map>_N), each one's component pressing on the triangle's outer face over its area
// (grain_pressure_<map>_Pa, fluid_pressure_<map>_Pa: positive pushes into the barrier) and, with both, their
// sum (pressure_<map>_Pa); a component only if the run has it (`grains`, `fluid`), zeros for a map never
// taken. Their times: barrier_maps.csv's last line, and the summary's times of the grains' and the fluid's
// largest normal forces (docs/geometry.md).
void write_facet_maps(const std::filesystem::path& dir, const geometry::TriangleMesh& mesh,
                      const analysis::FacetMaps& maps, bool grains, bool fluid);
void write_arching(const std::filesystem::path& dir, const analysis::ArchingMonitor& arching, double t0);
// Mixtures: volume fraction of large grains in slabs of the deposit (deposit_composition.csv).
void write_deposit_composition(const std::filesystem::path& dir, const scenario::ChannelCase& scene,
                               const dem::Particles& p);
// summary.json's barrier_face_x_m and barrier_face_normal: where the face is and the direction the force
// maps' normal component is taken along (the report's pressures over the barrier's height).
void add_barrier_face(JsonObject& js, const scenario::BarrierInfo& barrier);

}  // namespace sabo::io
