// SPDX-License-Identifier: MIT
#include "geometry/triangle_bins.h"

#include <algorithm>
#include <cmath>

namespace sabo::geometry {

namespace {

constexpr double max_bins = 1 << 20;  // bins stay a few MB for any mesh

Bounds box_of(const TriangleMesh& mesh, std::uint32_t t) {
    const Vec3 a = mesh.corner(t, 0), b = mesh.corner(t, 1), c = mesh.corner(t, 2);
    return {{std::min({a.x, b.x, c.x}), std::min({a.y, b.y, c.y}), std::min({a.z, b.z, c.z})},
            {std::max({a.x, b.x, c.x}), std::max({a.y, b.y, c.y}), std::max({a.z, b.z, c.z})}};
}

}  // namespace

TriangleBins::TriangleBins(const TriangleMesh& mesh, std::span<const std::uint32_t> triangles) {
    if (triangles.empty()) return;
    Bounds all = box_of(mesh, triangles[0]);
    double extent_sum = 0.0;
    for (const std::uint32_t t : triangles) {
        const Bounds b = box_of(mesh, t);
        all.lo = {std::min(all.lo.x, b.lo.x), std::min(all.lo.y, b.lo.y), std::min(all.lo.z, b.lo.z)};
        all.hi = {std::max(all.hi.x, b.hi.x), std::max(all.hi.y, b.hi.y), std::max(all.hi.z, b.hi.z)};
        const Vec3 s = b.size();
        extent_sum += std::max({s.x, s.y, s.z});
    }
    // A bin about a triangle's size: each triangle in a few bins, each bin holding a few triangles. A part of
    // large and small triangles gets the mean; the bins never outnumber max_bins.
    const Vec3 size = all.size();
    double cell = std::max(extent_sum / static_cast<double>(triangles.size()),
                           1e-6 * std::max({size.x, size.y, size.z, 1e-300}));
    const auto count = [&](double c) {
        return (std::floor(size.x / c) + 1) * (std::floor(size.y / c) + 1) * (std::floor(size.z / c) + 1);
    };
    while (count(cell) > max_bins) cell *= 1.25;
    lo_ = all.lo;
    inv_cell_ = 1.0 / cell;
    n_[0] = static_cast<int>(std::floor(size.x / cell)) + 1;
    n_[1] = static_cast<int>(std::floor(size.y / cell)) + 1;
    n_[2] = static_cast<int>(std::floor(size.z / cell)) + 1;

    triangle_.assign(triangles.begin(), triangles.end());
    sphere_.resize(triangles.size());
    for (std::size_t l = 0; l < triangles.size(); ++l) {
        const std::uint32_t t = triangles[l];
        const Vec3 c = (mesh.corner(t, 0) + mesh.corner(t, 1) + mesh.corner(t, 2)) / 3.0;
        double radius = 0.0;
        for (int k = 0; k < 3; ++k) radius = std::max(radius, norm(mesh.corner(t, k) - c));
        sphere_[l] = {c, radius};
    }
    // two passes: count per bin, then place (triangles ascending within each bin)
    start_.assign(static_cast<std::size_t>(n_[0]) * n_[1] * n_[2] + 1, 0);
    for (int pass = 0; pass < 2; ++pass) {
        std::vector<std::uint32_t> fill;
        if (pass == 1) {
            for (std::size_t b = 1; b < start_.size(); ++b) start_[b] += start_[b - 1];
            items_.resize(start_.back());
            fill.assign(start_.begin(), start_.end() - 1);
        }
        for (std::size_t l = 0; l < triangles.size(); ++l) {
            const Bounds b = box_of(mesh, triangles[l]);
            const int lo[3] = {bin_of(b.lo.x, 0), bin_of(b.lo.y, 1), bin_of(b.lo.z, 2)};
            const int hi[3] = {bin_of(b.hi.x, 0), bin_of(b.hi.y, 1), bin_of(b.hi.z, 2)};
            for (int z = lo[2]; z <= hi[2]; ++z)
                for (int y = lo[1]; y <= hi[1]; ++y)
                    for (int x = lo[0]; x <= hi[0]; ++x) {
                        if (pass == 0)
                            ++start_[index(x, y, z) + 1];
                        else
                            items_[fill[index(x, y, z)]++] = static_cast<std::uint32_t>(l);
                    }
        }
    }
}

int TriangleBins::bin_of(double v, int k) const {
    const double origin[3] = {lo_.x, lo_.y, lo_.z};
    return std::clamp(static_cast<int>(std::floor((v - origin[k]) * inv_cell_)), 0, n_[k] - 1);
}

bool TriangleBins::covered(const Vec3& p, double reach, int lo[3], int hi[3]) const {
    if (items_.empty()) return false;
    const double at[3] = {p.x, p.y, p.z}, origin[3] = {lo_.x, lo_.y, lo_.z};
    for (int k = 0; k < 3; ++k) {
        // the reach misses every bin
        if (at[k] + reach < origin[k] || (at[k] - reach - origin[k]) * inv_cell_ >= n_[k]) return false;
        lo[k] = bin_of(at[k] - reach, k);
        hi[k] = bin_of(at[k] + reach, k);
    }
    return true;
}

}  // namespace sabo::geometry
