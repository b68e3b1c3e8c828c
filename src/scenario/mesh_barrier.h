// SPDX-License-Identifier: MIT
// A barrier from the user's own triangle mesh (barrier.type = "mesh", docs/geometry.md): an STL file whose
// parts (one solid each: a pile, a wing wall, a sill) become the barrier's force elements, placed in the
// channel by a scale, rotations and an offset. Its piles and outlets across the channel follow from the
// parts' extents; its face from the mesh's upstream end. On the lattice its cells are those whose centres
// a part holds; for the grains each part is a wall (the nearest point of its triangles).
#pragma once
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "core/config.h"
#include "scenario/barrier.h"

namespace sabo::scenario {

// The mesh `table`.mesh_file names (relative to the case file), scaled (`table`.mesh_scale), rotated
// (`table`.mesh_rotation_{x,y,z}_deg, about x, then y, then z) and moved (`table`.mesh_offset_{x,y,z}_m);
// refused, naming `table`.mesh_file, when not closed or, if `inside`, outside the channel (`top`: the
// domain's height; else when more than ten times the channel's size), with a hint for a model in millimetres.
[[nodiscard]] std::shared_ptr<const geometry::TriangleMesh> placed_mesh(const Config& cfg,
                                                                        const std::string& table,
                                                                        const ChannelShape& channel,
                                                                        double top, bool inside = true);

// Reads [barrier]'s mesh keys (mesh_file relative to the case file, mesh_scale, mesh_rotation_{x,y,z}_deg,
// mesh_offset_{x,y,z}_m) and builds the barrier; refuses a mesh that is not closed or lies outside the
// channel (`top`: the domain's height).
// Each part becomes a wall for the grains (dem::Wall::mesh_part, appended to `walls`) and an element.
[[nodiscard]] BarrierInfo mesh_barrier(const Config& cfg, const ChannelShape& channel, double top,
                                       std::vector<dem::Wall>& walls);

// One line for `sabo check` and the log: the mesh's triangles, its parts with their volumes (and the lattice
// cells each holds, when `cells` has them), its bounding box and outlets.
[[nodiscard]] std::string describe_mesh(const BarrierInfo& barrier,
                                        const std::vector<std::size_t>& cells = {});

// The lattice cells (of side `dx`, from the origin) each part of a mesh barrier holds; refuses a part that
// holds none (too thin for the lattice). Empty for other barriers.
[[nodiscard]] std::vector<std::size_t> mesh_cells_on_lattice(const Config& cfg, const BarrierInfo& barrier,
                                                             double dx);

// A warning (empty: none) when the mesh named by `key` has triangles much finer than the grains (mean edge
// below a quarter of the smallest radius `r_min`): a grain near it meets dozens of triangles every step.
[[nodiscard]] std::string fine_mesh_warning(const std::string& key, const geometry::TriangleMesh& mesh,
                                            double r_min);
// Those of a case's barrier and channel meshes (each may be null; `r_min` 0: no grains, no warning).
[[nodiscard]] std::vector<std::string> fine_mesh_warnings(const geometry::TriangleMesh* barrier_mesh,
                                                          const geometry::TriangleMesh* channel_mesh,
                                                          double r_min);

}  // namespace sabo::scenario
