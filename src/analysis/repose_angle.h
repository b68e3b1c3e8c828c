// SPDX-License-Identifier: MIT
// Angle of repose of a heap on a plate (reference case C1): each side of the heap is split into parts along
// X; the highest grain top (z + r) in each part gives one point; a least-squares line through a side's points
// gives its slope; the angle is the mean of the two sides.
//
// Where a side ends (a choice the reference case leaves open, docs/analysis.md): at the crest, the part of
// the top profile (bins one diameter wide) within half a diameter of the heap's highest top. On a peaked heap
// that is the apex (± a few d); when the mass left on the plate was too small to reach a peak the heap
// has a flat top, and counting the plateau as "side" would flatten the fitted line. A crest that starts
// within a quarter of the half plate from its end leaves no distinct slope (a thin layer): that side is
// then the half plate.
#pragma once
#include <vector>

#include "core/vec3.h"

namespace sabo::analysis {

struct HeapPoint {
    double x = 0.0;  // m, centre of the highest grain of the part
    double z = 0.0;  // m, its top z + r
};

struct HeapSide {
    std::vector<HeapPoint> points;    // one per non-empty part
    double slope = 0.0;               // dz/dx of the fitted line
    double intercept = 0.0;           // m, z of the line at x = 0
    double angle_deg = 0.0;           // rise towards the crest: atan(slope) left, -atan(slope) right
    double r2 = 0.0;                  // coefficient of determination of the fit
    double rms = 0.0;                 // m, RMS distance of the points from the line (vertical)
    double x_from = 0.0, x_to = 0.0;  // m, extent of the side (plate edge → crest)
};

struct HeapAngle {
    HeapSide left, right;
    double angle_deg = 0.0;    // mean of both sides
    double height = 0.0;       // m, highest grain top above the plate
    bool flat_top = false;     // the crest is wider than 8 diameters
    std::size_t on_plate = 0;  // grains whose centre lies above the plate
};

struct PlateGeometry {
    double x_lo = 0.0, x_hi = 0.0;  // m, plate ends
    double z_top = 0.0;             // m, plate surface
    double diameter = 0.0;          // m, grain diameter (bin width of the top profile)
    int parts_per_side = 10;

    // Centre at or above the plate surface (the heap, and grains still leaving it through the outlets).
    [[nodiscard]] bool above(const Vec3& x) const { return x.z >= z_top; }
    // Above the plate surface and between its ends.
    [[nodiscard]] bool holds(const Vec3& x) const { return above(x) && x.x >= x_lo && x.x < x_hi; }
};

// Least-squares line z = a + b x through the points (≥ 2 distinct x), with R² and RMS residual.
void fit_line(HeapSide& side);

// Measures the heap formed by the grains (x, r); grains below the plate surface are ignored.
// Throws RunError when a side has fewer than three points (no heap).
[[nodiscard]] HeapAngle measure_heap(const std::vector<Vec3>& x, const std::vector<double>& r,
                                     std::size_t count, const PlateGeometry& plate);

}  // namespace sabo::analysis
