// SPDX-License-Identifier: MIT
// Which lattice cells each grain covers (the grain–fluid coupling), by one of two rules:
// - the cell centre (`cell_centre`): a cell belongs to a grain when its centre lies inside the sphere
//   (|x_c − x_p| < r_p), wholly (solid fraction ε = 1);
// - partial saturation (`psm`): every cell the sphere cuts belongs to it with the fraction ε of the cell's
//   volume inside the sphere (0 < ε ≤ 1; solid_fraction()).
// A cell in two overlapping grains belongs to one only, so nothing is counted twice: the one holding more of
// it (the larger ε), then the one it lies deeper in (the smaller |x_c − x_p| / r_p), then the lower grain
// index. Cells beyond the lattice are not covered by anything: a grain that leaves the lattice (or the part
// of it that sticks out) feels no fluid there.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
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

enum class CoverRule : std::uint8_t { cell_centre, psm };
inline constexpr std::array<std::string_view, 2> cover_rule_names{"cell_centre", "psm"};
[[nodiscard]] inline std::string_view name(CoverRule r) {
    return cover_rule_names[static_cast<std::size_t>(r)];
}

struct CoveredCell {
    std::size_t cell = 0;     // storage index
    std::uint32_t grain = 0;  // index of the grain in the spheres given to find()
    Vec3 centre{};            // the cell's centre, m
    double fraction = 1.0;  // ε: the share of the cell's volume inside the grain (1 by the cell-centre rule)
};

// The share of the unit cube centred at `d` inside the sphere of radius `rc` centred at the origin (cell
// units): 1 or 0 where the cube lies wholly inside or outside; otherwise the exact chord length through the
// cube along z, averaged over 89 columns on a Fibonacci lattice in x and y (a cell's error below 0.6 % for a
// surface across it in any direction; the errors of a sphere's cells cancel: their sum is its volume within
// 0.05 % at d/Δx ≈ 8).
[[nodiscard]] double solid_fraction(const Vec3& d, double rc);

// The cells of the frame's grid a grain would cover alone in an unbounded lattice (the lattice's bounds
// ignored): the number of cell centres inside the sphere (`cell_centre`), or its volume over Δx³ (`psm`:
// what the solid fractions of the cells it cuts add up to, within 0.05 % at d/Δx ≈ 8). The same on every
// rank of a divided run (the grid is global), so it can weight a grain's cells on each.
[[nodiscard]] double cells_covered_alone(const Vec3& x, double r, const LatticeFrame& frame, CoverRule rule);

// Finds the cells the given spheres (grains) cover, ascending by cell (the order the lattice wants them in).
// Each grain marks the cells of its bounding box that it covers in a per-cell owner array (a shared cell
// goes by the rule above) and in a bitmap of the covered cells; reading the bitmap word by word then
// gives the cells in ascending order without a sort, and clears both for the next call. Threads take slabs
// of planes (the result does not depend on their number). Memory: 16 bytes and a bit per stored lattice
// cell, allocated once, and 8 more with partial saturation.
class GrainCellFinder {
  public:
    // The cells of the spheres of centres `x` and radii `r` (the same count).
    void find(std::span<const Vec3> x, std::span<const double> r, const LatticeFrame& frame,
              CoverRule rule = CoverRule::cell_centre);
    [[nodiscard]] const std::vector<CoveredCell>& cells() const { return cells_; }

  private:
    std::vector<std::int32_t> owner_;  // per stored cell: the grain holding it (−1: none)
    std::vector<double> depth_;        // its |x_c − x_p|² / r_p²
    std::vector<double> fraction_;     // its ε (partial saturation only)
    std::vector<std::uint64_t> covered_;
    std::vector<CoveredCell> cells_;
    std::vector<std::size_t> offset_;         // where each thread's slab of cells starts in cells_
    std::vector<std::uint64_t> boxes_below_;  // per plane z: the grains' box cells in the planes below z
};

}  // namespace sabo::coupling
