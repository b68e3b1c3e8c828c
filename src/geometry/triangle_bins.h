// SPDX-License-Identifier: MIT
// A spatial index of some of a mesh's triangles (a part's): a uniform grid of bins over their bounding box,
// each listing the triangles whose bounding boxes overlap it. The triangles near a point are found among
// those of the few bins its reach covers instead of all the part's (docs/geometry.md): what lets a grain's
// neighbour list hold the triangles it may touch.
#pragma once
#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "geometry/triangle_mesh.h"

namespace sabo::geometry {

class TriangleBins {
  public:
    TriangleBins() = default;
    TriangleBins(const TriangleMesh& mesh, std::span<const std::uint32_t> triangles);

    // Into `out` (cleared first), ascending and each once: the triangles in the bins that the cube of half
    // side `reach` about p overlaps whose bounding spheres come within `reach` of p — every indexed triangle
    // within `reach` of p, and some farther.
    void near(const Vec3& p, double reach, std::vector<std::uint32_t>& out) const {
        near(p, reach, out, [](std::uint32_t) { return true; });
    }
    // The same, only the triangles for which keep(t) also holds (asked before the order is made, perhaps more
    // than once for a triangle).
    template <class Keep>
    void near(const Vec3& p, double reach, std::vector<std::uint32_t>& out, Keep keep) const {
        out.clear();
        int lo[3], hi[3];
        if (!covered(p, reach, lo, hi)) return;
        for (int z = lo[2]; z <= hi[2]; ++z)
            for (int y = lo[1]; y <= hi[1]; ++y)
                for (int x = lo[0]; x <= hi[0]; ++x) {
                    const std::size_t b = index(x, y, z);
                    for (std::uint32_t s = start_[b]; s < start_[b + 1]; ++s) {
                        const std::uint32_t l = items_[s];
                        // clear of the bounding sphere (a margin for round-off): clear of the triangle
                        const double around = reach + sphere_[l].radius;
                        if (norm2(p - sphere_[l].centre) <= around * around * (1.0 + 1e-9) &&
                            keep(triangle_[l]))
                            out.push_back(triangle_[l]);
                    }
                }
        std::sort(out.begin(), out.end());
        out.erase(std::unique(out.begin(), out.end()), out.end());
    }

    [[nodiscard]] std::size_t bins() const { return start_.empty() ? 0 : start_.size() - 1; }

  private:
    // The bins the cube of half side `reach` about p overlaps, per axis (false: none).
    bool covered(const Vec3& p, double reach, int lo[3], int hi[3]) const;
    // The bin along axis k holding coordinate v (clamped to the grid).
    [[nodiscard]] int bin_of(double v, int k) const;
    [[nodiscard]] std::size_t index(int x, int y, int z) const {
        return (static_cast<std::size_t>(z) * static_cast<std::size_t>(n_[1]) + static_cast<std::size_t>(y)) *
                   static_cast<std::size_t>(n_[0]) +
               static_cast<std::size_t>(x);
    }
    Vec3 lo_{};
    double inv_cell_ = 1.0;
    int n_[3] = {0, 0, 0};
    // the indexed triangles (their numbers in the mesh) and their bounding spheres; bin b holds the indices
    // into them items_[start_[b] .. start_[b + 1])
    struct Sphere {
        Vec3 centre;
        double radius = 0.0;
    };
    std::vector<std::uint32_t> triangle_;
    std::vector<Sphere> sphere_;
    std::vector<std::uint32_t> start_, items_;
};

}  // namespace sabo::geometry
