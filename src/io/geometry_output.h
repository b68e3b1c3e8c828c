// SPDX-License-Identifier: MIT
// The run's solid geometry as a surface for ParaView (geometry.vtp, docs/outputs.md): the walls — planes
// clipped to the domain's box, boxes with their six faces — and the fixed spheres of a barrier (each a
// faceted sphere) or the triangles of a barrier from a mesh, in the frames' coordinates, so that every view
// of the grains or the fluid has its channel and barrier around it. Written once when a run starts.
#pragma once
#include <filesystem>
#include <span>

#include "core/vec3.h"
#include "dem/particles.h"
#include "dem/walls.h"
#include "geometry/triangle_mesh.h"

namespace sabo::io {

// `box`: the domain's extent from the origin (the planes are clipped to it); the fixed spheres are
// particles.x/r from particles.n_mobile on.
// `mesh` (may be null): a barrier of triangles, its parts the barrier's elements.
void write_geometry(const std::filesystem::path& file, std::span<const dem::Wall> walls,
                    const dem::Particles& particles, const Vec3& box,
                    const geometry::TriangleMesh* mesh = nullptr);

}  // namespace sabo::io
