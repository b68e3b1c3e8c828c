// SPDX-License-Identifier: MIT
// Grains fed into a channel from a hydrograph ([inflow]): every batch interval Δt_b the grains' volume the
// hydrograph carried through the section in that interval, ∫ Q c dt, is placed at random, without overlap
// (with each other and with the grains already there), in the section's zone X in [x0, x0 + L], across the
// channel, from the bed up to the flow's depth, moving down the channel at the section's velocity u; L = u
// Δt_b, so that a grain that entered at the interval's start has just reached the zone's far end (the bed:
// the inclined plane, or the highest top of a channel mesh's relief under the zone, `base`; no grain is
// placed against the mesh's walls where they stand inside the channel's width). What a batch cannot place
// (the zone still full) is carried over to the next: the inserted volume follows the hydrograph's integral to
// within one grain. Frame: X down-slope, Y across, Z normal to the bed.
#pragma once
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/config.h"
#include "dem/grain_records.h"
#include "dem/particles.h"
#include "geometry/triangle_mesh.h"
#include "scenario/hydrograph.h"

namespace sabo::scenario {

// The solid fraction up to which grains are placed at random (random sequential placement slows to a crawl
// beyond ~0.3 in a layer a few grains deep): a denser flow's grains enter in a deeper layer at this fraction
// and settle.
inline constexpr double inflow_placement_fraction = 0.25;

struct InflowSettings {
    Hydrograph hydrograph;
    double x0 = 0.0;        // the zone's upstream end, m
    double velocity = 0.0;  // u, m/s, down the channel
    double length = 0.0;    // L = u Δt_b, m (the run rounds Δt_b to whole DEM steps and L with it)
    double width = 0.0;     // the channel's, m
    double height = 0.0;    // its side walls', m: no batch is placed higher
    double base = 0.0;      // the bed under the zone: the relief's highest level there, m above the plane
    // the channel's mesh (none: the box alone) and its triangles that reach the zone, which no grain is
    // placed against, and the side walls among their parts with their bounds (a grain wholly inside a thick
    // wall touches none of its triangles)
    struct MeshPart {
        std::size_t part = 0;
        geometry::Bounds bounds;
    };
    std::shared_ptr<const geometry::TriangleMesh> mesh;
    std::vector<std::uint32_t> mesh_near;
    std::vector<MeshPart> walls_near;
    double radius = 0.05;     // the grains' mean radius when the hydrograph has none, m
    double spread = 0.05;     // radii uniform in [1 − s, 1 + s] × the mean
    double density = 2500.0;  // kg/m³
    std::uint64_t seed = 1;
    [[nodiscard]] double r_min() const;
    [[nodiscard]] double r_max() const;
    // The depth of the zone the grains of a batch of solid volume `solid` are placed in, m.
    [[nodiscard]] double depth(double solid, double solid_fraction) const;
    // The deepest batch: at the hydrograph's largest discharge and the solid fraction it is placed at, m.
    [[nodiscard]] double deepest() const;
};

// [inflow] of a channel case (none when the case has no [inflow]); `height` the side walls', `barrier_x`
// where the zone must end before.
[[nodiscard]] std::optional<InflowSettings> read_inflow(const Config& cfg, double width, double height,
                                                        double barrier_x);

// For the log: where the zone stands on the bed's relief and meets a mesh (", from Z 0.200 m (the bed's
// relief), clear of the 8 triangles of the channel mesh there"), or nothing on the plane of the box.
[[nodiscard]] std::string inflow_bed_note(const InflowSettings& s);

// The grains of one batch: `solid` m³ (the interval's share plus what earlier batches could not place) at the
// hydrograph's state at time t (clamped to its rows' times); `present` the grains already in the run (their
// mobile ones). Returns the records to add (dem::DemSolver::add_mobile) and sets `placed` to their volume.
[[nodiscard]] std::vector<dem::GrainRecord> inflow_batch(const InflowSettings& s, double t, double solid,
                                                         std::uint64_t batch, const dem::Particles& present,
                                                         double& placed);

}  // namespace sabo::scenario
