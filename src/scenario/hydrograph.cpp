// SPDX-License-Identifier: MIT
#include "scenario/hydrograph.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "scenario/csv_table.h"

namespace sabo::scenario {

Hydrograph Hydrograph::read(const std::filesystem::path& file) {
    const CsvTable table = read_csv_table(file, "the hydrograph (inflow.hydrograph_file)", 1000000);
    const std::vector<std::string> needed{"time_s", "discharge_m3_s", "solid_fraction"};
    const bool graded = table.header.size() == 4 && table.header[3] == "radius_mean_m";
    if (table.header.size() < 3 || !std::equal(needed.begin(), needed.end(), table.header.begin()) ||
        (table.header.size() != 3 && !graded))
        throw InputError(
            fmt::format("{}: line 1: the header must be 'time_s,discharge_m3_s,solid_fraction' or "
                        "'time_s,discharge_m3_s,solid_fraction,radius_mean_m' (inflow.hydrograph_file)",
                        file.string()));
    Hydrograph h;
    for (const auto& row : table.rows) {
        h.time_.push_back(row[0]);
        h.discharge_.push_back(row[1]);
        h.solid_fraction_.push_back(row[2]);
        if (graded) h.radius_.push_back(row[3]);
    }
    // the rows' own lines in the messages
    for (std::size_t k = 0; k < table.rows.size(); ++k) {
        const std::string where = fmt::format("{}: line {}", file.string(), table.lines[k]);
        const auto& row = table.rows[k];
        if (row[0] < 0.0) throw InputError(where + ": time_s must be ≥ 0 (inflow.hydrograph_file)");
        if (k > 0 && !(row[0] > table.rows[k - 1][0]))
            throw InputError(where + ": time_s must increase from row to row (inflow.hydrograph_file)");
        if (row[1] < 0.0) throw InputError(where + ": discharge_m3_s must be ≥ 0 (inflow.hydrograph_file)");
        if (row[2] < 0.0 || row[2] > 1.0)
            throw InputError(where + ": solid_fraction must be in [0, 1] (inflow.hydrograph_file)");
        if (graded && !(row[3] > 0.0))
            throw InputError(where + ": radius_mean_m must be positive (inflow.hydrograph_file)");
    }
    h.check(fmt::format("{} (inflow.hydrograph_file)", file.string()));
    return h;
}

Hydrograph::Hydrograph(std::vector<double> time, std::vector<double> discharge,
                       std::vector<double> solid_fraction, std::vector<double> radius)
    : time_(std::move(time)),
      discharge_(std::move(discharge)),
      solid_fraction_(std::move(solid_fraction)),
      radius_(std::move(radius)) {
    check("hydrograph");
}

void Hydrograph::check(const std::string& where) const {
    const std::size_t n = time_.size();
    if (n < 2) throw InputError(where + ": at least two rows are needed (a start and an end)");
    if (discharge_.size() != n || solid_fraction_.size() != n || (!radius_.empty() && radius_.size() != n))
        throw InputError(where + ": columns of different lengths");
    for (std::size_t k = 0; k < n; ++k) {
        if (!(time_[k] >= 0.0) || (k > 0 && !(time_[k] > time_[k - 1])))
            throw InputError(where + ": times must increase from ≥ 0");
        if (!(discharge_[k] >= 0.0) || !(solid_fraction_[k] >= 0.0 && solid_fraction_[k] <= 1.0) ||
            (!radius_.empty() && !(radius_[k] > 0.0)))
            throw InputError(where +
                             ": a discharge below 0, a solid fraction outside [0, 1] or a radius ≤ 0");
    }
}

double Hydrograph::at(const std::vector<double>& time, const std::vector<double>& v, double t) {
    if (time.empty() || t < time.front() || t > time.back()) return 0.0;
    const auto hi = std::upper_bound(time.begin(), time.end(), t);
    if (hi == time.end()) return v.back();
    const auto k = static_cast<std::size_t>(hi - time.begin());
    const double s = (t - time[k - 1]) / (time[k] - time[k - 1]);
    return v[k - 1] + s * (v[k] - v[k - 1]);
}

double Hydrograph::discharge(double t) const {
    return at(time_, discharge_, t);
}
double Hydrograph::solid_fraction(double t) const {
    return at(time_, solid_fraction_, t);
}

double Hydrograph::radius(double t, double fallback) const {
    if (radius_.empty() || time_.empty()) return fallback;
    return at(time_, radius_, std::clamp(t, time_.front(), time_.back()));
}

double Hydrograph::smallest_radius() const {
    return radius_.empty() ? 0.0 : *std::min_element(radius_.begin(), radius_.end());
}
double Hydrograph::largest_radius() const {
    return radius_.empty() ? 0.0 : *std::max_element(radius_.begin(), radius_.end());
}
double Hydrograph::largest_discharge() const {
    return discharge_.empty() ? 0.0 : *std::max_element(discharge_.begin(), discharge_.end());
}
double Hydrograph::largest_solid_fraction() const {
    double c = 0.0;
    for (std::size_t k = 0; k < time_.size(); ++k)
        if (discharge_[k] > 0.0) c = std::max(c, solid_fraction_[k]);
    return c;
}

double Hydrograph::integral(const std::vector<double>& f, const std::vector<double>* g, double t0,
                            double t1) const {
    if (time_.empty()) return 0.0;
    t0 = std::max(t0, time_.front());
    t1 = std::min(t1, time_.back());
    if (!(t1 > t0)) return 0.0;
    const auto value = [&](double t) { return at(time_, f, t) * (g != nullptr ? at(time_, *g, t) : 1.0); };
    double sum = 0.0;
    // Simpson's rule on every piece between rows: exact for the product of two linear functions
    double a = t0;
    auto k = static_cast<std::size_t>(std::upper_bound(time_.begin(), time_.end(), t0) - time_.begin());
    while (a < t1) {
        const double b = k < time_.size() ? std::min(time_[k], t1) : t1;
        if (b > a) sum += (b - a) / 6.0 * (value(a) + 4.0 * value(0.5 * (a + b)) + value(b));
        a = b;
        ++k;
    }
    return sum;
}

double Hydrograph::solid_volume(double t0, double t1) const {
    return integral(discharge_, &solid_fraction_, t0, t1);
}
double Hydrograph::volume(double t0, double t1) const {
    return integral(discharge_, nullptr, t0, t1);
}

}  // namespace sabo::scenario
