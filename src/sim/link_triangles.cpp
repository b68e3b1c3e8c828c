// SPDX-License-Identifier: MIT
#include "sim/link_triangles.h"

#include <fmt/format.h>

#include <limits>
#include <stdexcept>

#include "geometry/mesh_queries.h"
#include "lbm/d3q19.h"

namespace sabo::sim {

std::span<const std::uint32_t> LinkTriangles::of(const lbm::BarrierLinks& links,
                                                 const geometry::TriangleMesh& mesh,
                                                 std::span<const std::size_t> element_part,
                                                 const std::function<Vec3(std::uint32_t)>& centre,
                                                 double dx) {
    if (version_ == links.version && triangle_.size() == links.size()) return triangle_;
    if (bins_.empty()) {
        std::vector<std::vector<std::uint32_t>> of_part(mesh.parts());
        for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
            of_part[mesh.part[t]].push_back(static_cast<std::uint32_t>(t));
        for (const auto& triangles : of_part) bins_.emplace_back(mesh, triangles);
    }
    triangle_.resize(links.size());
    std::vector<std::uint32_t> near;
    const double extent = norm(mesh.bounds().size()) + dx;
    for (std::size_t j = 0; j < links.size(); ++j) {
        const std::size_t e = links.element[j];
        if (e == 0 || e > element_part.size())
            throw std::logic_error(
                fmt::format("LinkTriangles: a barrier link of element {} of {}", e, element_part.size()));
        const std::size_t part = element_part[e - 1];
        const int i = links.direction[j];
        const Vec3 c = centre(links.cell[j]);
        const Vec3 p = c + 0.5 * dx *
                               Vec3{static_cast<double>(lbm::cx[i]), static_cast<double>(lbm::cy[i]),
                                    static_cast<double>(lbm::cz[i])};
        // The wall lies within half a diagonal link of p: a reach of dx finds it but where a cell's centre
        // lies on a face; farther reaches until some triangle comes. A diagonal link's midpoint may lie on
        // the edge between two triangles of a face (a face cut at a cell boundary): of equally near triangles
        // the one nearer the wet cell's centre takes it — the one in front of the cell, whose wall patch the
        // link belongs to (the lowest-numbered would take every tied link along the edge); then the
        // lowest-numbered.
        const double tie = 1e-9 * dx * dx;
        double best = std::numeric_limits<double>::infinity(), best_from_cell = best;
        for (double reach = dx; best == std::numeric_limits<double>::infinity(); reach *= 2.0) {
            bins_[part].near(p, reach, near);
            for (const std::uint32_t t : near) {  // (ascending)
                const double d = norm2(geometry::closest_point(mesh, t, p) - p);
                if (d > best + tie) continue;
                const double from_cell = norm2(geometry::closest_point(mesh, t, c) - c);
                if (d < best - tie || from_cell < best_from_cell - tie) {
                    best = std::min(best, d);
                    best_from_cell = from_cell;
                    triangle_[j] = t;
                }
            }
            if (reach > extent && best == std::numeric_limits<double>::infinity())
                throw std::logic_error("LinkTriangles: a part without triangles");
        }
    }
    version_ = links.version;
    return triangle_;
}

}  // namespace sabo::sim
