// SPDX-License-Identifier: MIT
// Finds whether a sphere overlaps one of the spheres kept so far in a box of cells one largest diameter wide
// (`touching`: whether |x_i − x_j| = r_i + r_j counts as overlapping): only the 27 cells around it are
// searched. Placing grains at random and reading them from a file both check every new grain this way (not
// against every grain before it).
#pragma once
#include <algorithm>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/vec3.h"
#include "dem/particles.h"

namespace sabo::scenario {

class OverlapGrid {
  public:
    // The box [lo, hi] (centres outside it fall in its edge cells) and the largest grain diameter, m.
    OverlapGrid(const Vec3& lo, const Vec3& hi, double largest_diameter, bool touching)
        : touching_(touching),
          lo_(lo),
          cell_(largest_diameter),
          nx_(static_cast<int>((hi.x - lo.x) / cell_) + 1),
          ny_(static_cast<int>((hi.y - lo.y) / cell_) + 1),
          nz_(static_cast<int>((hi.z - lo.z) / cell_) + 1),
          cells_(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_) *
                 static_cast<std::size_t>(nz_)) {}

    // The first kept sphere (an index into `kept`) that a sphere at x of radius r overlaps, if any.
    [[nodiscard]] std::optional<std::uint32_t> overlap(const Vec3& x, double r,
                                                       const dem::Particles& kept) const {
        const auto [i, j, k] = slot(x);
        for (int dk = -1; dk <= 1; ++dk)
            for (int dj = -1; dj <= 1; ++dj)
                for (int di = -1; di <= 1; ++di) {
                    const int a = i + di, b = j + dj, d = k + dk;
                    if (a < 0 || b < 0 || d < 0 || a >= nx_ || b >= ny_ || d >= nz_) continue;
                    for (const std::uint32_t q : cells_[index(a, b, d)]) {
                        const double reach = r + kept.r[q];
                        const double d2 = norm2(x - kept.x[q]);
                        if (d2 < reach * reach || (touching_ && d2 == reach * reach)) return q;
                    }
                }
        return std::nullopt;
    }
    // Keeps sphere `q` (its index in `kept`) centred at x.
    void add(std::uint32_t q, const Vec3& x) {
        const auto [i, j, k] = slot(x);
        cells_[index(i, j, k)].push_back(q);
    }

  private:
    struct Slot {
        int i, j, k;
    };
    [[nodiscard]] Slot slot(const Vec3& x) const {
        return {std::clamp(static_cast<int>((x.x - lo_.x) / cell_), 0, nx_ - 1),
                std::clamp(static_cast<int>((x.y - lo_.y) / cell_), 0, ny_ - 1),
                std::clamp(static_cast<int>((x.z - lo_.z) / cell_), 0, nz_ - 1)};
    }
    [[nodiscard]] std::size_t index(int i, int j, int k) const {
        return (static_cast<std::size_t>(k) * static_cast<std::size_t>(ny_) + static_cast<std::size_t>(j)) *
                   static_cast<std::size_t>(nx_) +
               static_cast<std::size_t>(i);
    }

    bool touching_;
    Vec3 lo_;
    double cell_;
    int nx_, ny_, nz_;
    std::vector<std::vector<std::uint32_t>> cells_;
};

}  // namespace sabo::scenario
