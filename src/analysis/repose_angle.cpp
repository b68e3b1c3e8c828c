// SPDX-License-Identifier: MIT
#include "analysis/repose_angle.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/error.h"

namespace sabo::analysis {

void fit_line(HeapSide& side) {
    const auto n = static_cast<double>(side.points.size());
    double sx = 0.0, sz = 0.0;
    for (const auto& p : side.points) {
        sx += p.x;
        sz += p.z;
    }
    const double mx = sx / n, mz = sz / n;
    double sxx = 0.0, sxz = 0.0, szz = 0.0;
    for (const auto& p : side.points) {
        sxx += (p.x - mx) * (p.x - mx);
        sxz += (p.x - mx) * (p.z - mz);
        szz += (p.z - mz) * (p.z - mz);
    }
    if (!(sxx > 0.0)) throw RunError("heap angle: the points of a side share one x (no line to fit)");
    side.slope = sxz / sxx;
    side.intercept = mz - side.slope * mx;
    double ss_res = 0.0;
    for (const auto& p : side.points) {
        const double e = p.z - (side.intercept + side.slope * p.x);
        ss_res += e * e;
    }
    side.r2 = szz > 0.0 ? 1.0 - ss_res / szz : 1.0;
    side.rms = std::sqrt(ss_res / n);
}

namespace {

// Highest grain top per part of [from, to), one point per non-empty part.
std::vector<HeapPoint> part_tops(const std::vector<Vec3>& x, const std::vector<double>& r, std::size_t count,
                                 const PlateGeometry& plate, double from, double to, int parts) {
    std::vector<HeapPoint> best(static_cast<std::size_t>(parts),
                                {0.0, -std::numeric_limits<double>::infinity()});
    const double width = (to - from) / parts;
    for (std::size_t i = 0; i < count; ++i) {
        if (!plate.above(x[i]) || x[i].x < from || x[i].x >= to) continue;
        const auto p = std::min<std::size_t>(static_cast<std::size_t>((x[i].x - from) / width),
                                             static_cast<std::size_t>(parts) - 1);
        if (x[i].z + r[i] > best[p].z) best[p] = {x[i].x, x[i].z + r[i]};
    }
    std::vector<HeapPoint> out;
    for (const auto& b : best) {
        if (std::isfinite(b.z)) out.push_back(b);
    }
    return out;
}

}  // namespace

HeapAngle measure_heap(const std::vector<Vec3>& x, const std::vector<double>& r, std::size_t count,
                       const PlateGeometry& plate) {
    HeapAngle h;
    const double length = plate.x_hi - plate.x_lo;
    // top profile in bins one diameter wide: where the crest begins
    const auto bins = std::max<std::size_t>(2, static_cast<std::size_t>(length / plate.diameter));
    std::vector<double> top(bins, plate.z_top);
    for (std::size_t i = 0; i < count; ++i) {
        if (!plate.holds(x[i])) continue;
        ++h.on_plate;
        const auto b = std::min(bins - 1, static_cast<std::size_t>((x[i].x - plate.x_lo) / length * bins));
        top[b] = std::max(top[b], x[i].z + r[i]);
    }
    const double highest = *std::max_element(top.begin(), top.end());
    h.height = highest - plate.z_top;
    const double bin_w = length / static_cast<double>(bins);
    // crest: the top-profile bins within half a diameter of the highest top; the left side ends at the
    // first of them, the right side starts after the last. Flat-topped: the crest is wider than 8 d.
    std::size_t first = bins, last = 0;
    for (std::size_t b = 0; b < bins; ++b) {
        if (top[b] >= highest - 0.5 * plate.diameter) {
            first = std::min(first, b);
            last = b;
        }
    }
    double crest_left = plate.x_lo + (static_cast<double>(first) + 0.5) * bin_w;
    double crest_right = plate.x_lo + (static_cast<double>(last) + 0.5) * bin_w;
    h.flat_top = crest_right - crest_left > 8.0 * plate.diameter;
    // A crest that starts within a quarter of the half plate from its end leaves no distinct slope (a
    // layer a grain or two high, from low friction): that side is the half plate, and its angle small.
    const double mid = 0.5 * (plate.x_lo + plate.x_hi), quarter = 0.125 * length;
    if (crest_left - plate.x_lo < quarter) crest_left = mid;
    if (plate.x_hi - crest_right < quarter) crest_right = mid;
    h.left.x_from = plate.x_lo;
    h.left.x_to = crest_left;
    h.right.x_from = crest_right;
    h.right.x_to = plate.x_hi;
    const int parts = plate.parts_per_side;
    h.left.points = part_tops(x, r, count, plate, plate.x_lo, crest_left, parts);
    h.right.points = part_tops(x, r, count, plate, crest_right, plate.x_hi, parts);
    for (HeapSide* side : {&h.left, &h.right}) {
        if (side->points.size() < 3) {
            throw RunError(fmt::format(
                "heap angle: only {} of {} parts of a side hold grains above the plate (no heap formed)",
                side->points.size(), parts));
        }
        fit_line(*side);
    }
    // both angles positive when the side rises towards the crest
    h.left.angle_deg = std::atan(h.left.slope) * 180.0 / std::numbers::pi;
    h.right.angle_deg = -std::atan(h.right.slope) * 180.0 / std::numbers::pi;
    h.angle_deg = 0.5 * (h.left.angle_deg + h.right.angle_deg);
    return h;
}

}  // namespace sabo::analysis
