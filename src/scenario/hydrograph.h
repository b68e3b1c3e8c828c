// SPDX-License-Identifier: MIT
// A hydrograph: what enters a channel through its inflow section over time, from a CSV file with the columns
// time_s, discharge_m3_s (the bulk discharge Q: grains and fluid), solid_fraction (c, the grains' share of
// its volume) and optionally radius_mean_m (the grains' mean radius: a grading that changes with time).
// Between rows each value varies linearly; before the first time and after the last nothing enters.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

namespace sabo::scenario {

class Hydrograph {
  public:
    // Reads and checks `file` (named by inflow.hydrograph_file in messages): at least two rows, times
    // increasing from ≥ 0, Q ≥ 0, c in [0, 1], radii > 0.
    static Hydrograph read(const std::filesystem::path& file);
    // None: nothing enters.
    Hydrograph() = default;
    // From columns (tests; the same checks).
    Hydrograph(std::vector<double> time, std::vector<double> discharge, std::vector<double> solid_fraction,
               std::vector<double> radius = {});

    [[nodiscard]] double discharge(double t) const;       // Q, m³/s
    [[nodiscard]] double solid_fraction(double t) const;  // c
    // The grains' mean radius at t, m; `fallback` when the file has no such column.
    [[nodiscard]] double radius(double t, double fallback) const;
    [[nodiscard]] bool graded() const { return !radius_.empty(); }
    [[nodiscard]] double smallest_radius() const;
    [[nodiscard]] double largest_radius() const;
    // ∫ Q c dt over [t0, t1], m³ (exact: Q c is quadratic between rows); ∫ Q dt likewise.
    [[nodiscard]] double solid_volume(double t0, double t1) const;
    [[nodiscard]] double volume(double t0, double t1) const;
    // ∫ Q (1 − c) dt: the fluid's share (the whole volume where c = 0), m³; Q (1 − c) at t, m³/s.
    [[nodiscard]] double fluid_volume(double t0, double t1) const {
        return volume(t0, t1) - solid_volume(t0, t1);
    }
    [[nodiscard]] double fluid_discharge(double t) const { return discharge(t) * (1.0 - solid_fraction(t)); }
    [[nodiscard]] double start() const { return time_.empty() ? 0.0 : time_.front(); }
    [[nodiscard]] double end() const { return time_.empty() ? 0.0 : time_.back(); }
    [[nodiscard]] double largest_discharge() const;
    [[nodiscard]] std::size_t rows() const { return time_.size(); }
    [[nodiscard]] double largest_solid_fraction() const;

  private:
    void check(const std::string& where) const;
    // ∫ f g dt over [t0, t1] for the piecewise-linear columns f and g (g empty: 1).
    [[nodiscard]] double integral(const std::vector<double>& f, const std::vector<double>* g, double t0,
                                  double t1) const;
    [[nodiscard]] static double at(const std::vector<double>& time, const std::vector<double>& v, double t);
    std::vector<double> time_, discharge_, solid_fraction_, radius_;
};

}  // namespace sabo::scenario
