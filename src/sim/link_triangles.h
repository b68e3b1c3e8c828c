// SPDX-License-Identifier: MIT
// Which triangle of a mesh barrier each of the lattice's barrier links pushes on (docs/geometry.md, "Force
// maps on the mesh"): the triangle of the link's element's part nearest the link's midpoint — half-way from
// the wet cell's centre to the obstacle's, where the half-way bounce-back puts the wall. Found once per list
// of links (they change with a face move or a checkpoint read, not with the flow).
#pragma once
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "core/vec3.h"
#include "geometry/triangle_bins.h"
#include "geometry/triangle_mesh.h"
#include "lbm/barrier_links.h"

namespace sabo::sim {

class LinkTriangles {
  public:
    // Each link's triangle in `mesh`, whose part element_part[e − 1] is the lattice's element e; `centre(k)`:
    // the centre of stored cell k, m; `dx` the cell's size, m. Done again only when the list changed.
    std::span<const std::uint32_t> of(const lbm::BarrierLinks& links, const geometry::TriangleMesh& mesh,
                                      std::span<const std::size_t> element_part,
                                      const std::function<Vec3(std::uint32_t)>& centre, double dx);

  private:
    std::vector<std::uint32_t> triangle_;
    std::uint64_t version_ = 0;
    std::vector<geometry::TriangleBins> bins_;  // per part (built at the first use)
};

}  // namespace sabo::sim
