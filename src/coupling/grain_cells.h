// SPDX-License-Identifier: MIT
// Which lattice cells each grain covers (the grain–fluid coupling): a cell belongs to a grain when the
// cell's centre lies inside the sphere (|x_c − x_p| < r_p). A cell inside two overlapping grains belongs to
// the one it lies deeper in (the smaller |x_c − x_p| / r_p; equal depths: the lower grain index), so each
// cell exchanges momentum with one grain only. Cells beyond the lattice are not covered by anything: a
// grain that leaves the lattice (or the part of it that sticks out) feels no fluid there.
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/vec3.h"

namespace sabo::coupling {

// The lattice in the grains' frame: cell (x, y, z) has its centre at origin + (x+½, y+½, z+½) Δx and is
// stored at x + row·y + plane·z (the lattice's padded rows).
struct LatticeFrame {
    Vec3 origin{};
    double dx = 1.0;  // m
    int nx = 0, ny = 0, nz = 0;
    std::size_t row = 0, plane = 0;
    [[nodiscard]] Vec3 centre(int x, int y, int z) const {
        return origin + Vec3{(x + 0.5) * dx, (y + 0.5) * dx, (z + 0.5) * dx};
    }
};

struct CoveredCell {
    std::size_t cell = 0;     // storage index
    std::uint32_t grain = 0;  // index of the grain in the spheres given to find()
    Vec3 centre{};            // the cell's centre, m
};

// The number of cell centres of the frame's grid inside the sphere (|x_c − x| < r), the lattice's bounds
// ignored: the cells a grain would cover alone in an unbounded lattice. The same on every rank of a divided
// run (the grid is global), so it can weight a grain's cells on each.
[[nodiscard]] std::size_t cell_centres_inside(const Vec3& x, double r, const LatticeFrame& frame);

// Finds the cells the given spheres (grains) cover, ascending by cell (the order the lattice wants them in).
// Each grain marks the cells of its bounding box whose centre it holds in a per-cell owner array (the deeper
// grain wins a shared cell) and in a bitmap of the covered cells; reading the bitmap word by word then
// gives the cells in ascending order without a sort, and clears both for the next call. Threads take slabs
// of planes (the result does not depend on their number). Memory: 16 bytes and a bit per stored lattice
// cell, allocated once.
class GrainCellFinder {
  public:
    // The cells of the spheres of centres `x` and radii `r` (the same count).
    void find(std::span<const Vec3> x, std::span<const double> r, const LatticeFrame& frame);
    [[nodiscard]] const std::vector<CoveredCell>& cells() const { return cells_; }

  private:
    std::vector<std::int32_t> owner_;  // per stored cell: the grain holding it (−1: none)
    std::vector<double> depth_;        // its |x_c − x_p|² / r_p²
    std::vector<std::uint64_t> covered_;
    std::vector<CoveredCell> cells_;
    std::vector<std::size_t> offset_;  // where each thread's slab of cells starts in cells_
};

}  // namespace sabo::coupling
