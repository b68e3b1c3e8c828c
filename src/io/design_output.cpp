// SPDX-License-Identifier: MIT
#include "io/design_output.h"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/error.h"
#include "io/atomic_file.h"

namespace sabo::io {

using analysis::design::Comparison;
using analysis::design::MeasuredRun;

namespace {

// The numbers of MeasuredRun by their summary.json names (one list for writing and reading).
template <class Run, class Visit>
void visit_numbers(Run& r, Visit&& visit) {
    visit("approach_flow_depth_m", r.approach.depth);
    visit("approach_velocity_m_s", r.approach.velocity);
    visit("approach_bulk_density_kg_m3", r.approach.density);
    visit("gravity_m_s2", r.approach.g);
    visit("approach_front_velocity_m_s", r.front_velocity);
    visit("approach_peak_discharge_m3_s", r.peak_discharge);
    visit("approach_solid_fraction", r.solid_fraction);
    visit("barrier_width_m", r.width);
    visit("peak_normal_force_N", r.peak_normal_force);
    visit("static_normal_force_N", r.static_normal_force);
    visit("deposit_depth_m", r.deposit_depth);
    visit("deposit_bulk_density_kg_m3", r.deposit_density);
    visit("slope_deg", r.slope_deg);
    visit("barrier_height_m", r.barrier_height);
    visit("d95_m", r.d95);
    visit("d_max_m", r.d_max);
    visit("grain_density_kg_m3", r.grain_density);
    visit("retained_fraction", r.retained_fraction);
}

std::string csv_text(std::string s) {
    for (char& c : s)
        if (c == ',') c = ';';
    return s;
}

std::string number(double v) {
    return std::isfinite(v) ? fmt::format("{:.6g}", v) : "";
}

}  // namespace

JsonObject design_inputs_json(const MeasuredRun& run) {
    JsonObject js;
    visit_numbers(run, [&](const char* key, double v) { js.number(key, v); });
    std::vector<double> widths;
    for (const auto& o : run.openings) widths.push_back(o.width);
    js.numbers("opening_widths_m", widths);
    return js;
}

MeasuredRun read_design_inputs(const std::filesystem::path& summary_json) {
    std::ifstream in(summary_json);
    if (!in)
        throw InputError(
            fmt::format("{}: cannot be read (is it a finished run's folder?)", summary_json.string()));
    nlohmann::json doc;
    try {
        doc = nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
        throw InputError(fmt::format("{}: not valid JSON ({})", summary_json.string(), e.what()));
    }
    const auto fail = [&](const std::string& what) {
        throw InputError(fmt::format("{}: {}", summary_json.string(), what));
    };
    if (!doc.is_object() || !doc.contains("design_inputs") || !doc["design_inputs"].is_object())
        fail(
            "has no \"design_inputs\": only channel and debris runs with a barrier have them "
            "(rerun the case with this version)");
    const auto& d = doc["design_inputs"];
    MeasuredRun run;
    visit_numbers(run, [&](const char* key, double& v) {
        if (!d.contains(key)) fail(fmt::format("design_inputs.{} is missing", key));
        if (d[key].is_null()) {
            v = std::nan("");
        } else if (d[key].is_number()) {
            v = d[key].get<double>();
        } else {
            fail(fmt::format("design_inputs.{} is not a number", key));
        }
    });
    if (!d.contains("opening_widths_m") || !d["opening_widths_m"].is_array())
        fail("design_inputs.opening_widths_m is missing or not a list");
    for (const auto& w : d["opening_widths_m"]) {
        if (!w.is_number()) fail("design_inputs.opening_widths_m holds a value that is not a number");
        run.openings.push_back({w.get<double>(), run.barrier_height, true});
    }
    return run;
}

void write_design_comparison(const std::filesystem::path& out_dir, const Comparison& c) {
    std::string csv =
        "group,reference,formula,coefficient,predicted_low,predicted_high,simulated,unit,note\n";
    for (const auto& r : c.rows)
        csv += fmt::format("{},{},{},{},{},{},{},{},{}\n", r.group, csv_text(r.reference),
                           csv_text(r.formula), csv_text(r.coefficient), number(r.low), number(r.high),
                           number(r.simulated), r.unit, csv_text(r.note));
    for (const auto& k : c.coefficients)
        csv += fmt::format("back-calculated,{},{},,{},{},,-,\n", k.name, csv_text(k.definition),
                           number(k.value), number(k.value));
    csv += fmt::format("typology,Wehrmann et al. (2006) as read in docs/design.md,,,,,,,{}\n", c.typology);
    write_text_atomically(out_dir / "design_comparison.csv", csv);
}

std::string design_table(const Comparison& c, bool with_simulated) {
    std::ostringstream out;
    const auto range = [](double lo, double hi) {
        if (!std::isfinite(lo)) return std::string("-");
        return lo == hi ? fmt::format("{:.4g}", lo) : fmt::format("{:.4g} - {:.4g}", lo, hi);
    };
    std::string group;
    for (const auto& r : c.rows) {
        if (r.group != group) {
            group = r.group;
            out << fmt::format("\n{:<10} {:<52} {:<16} {:>21} {}\n", group, "reference", "coefficient",
                               "predicted [" + r.unit + "]", with_simulated ? "simulated" : "");
        }
        out << fmt::format(
            "{:<10} {:<52} {:<16} {:>21} {}\n", "", r.reference, r.coefficient, range(r.low, r.high),
            with_simulated && std::isfinite(r.simulated) ? fmt::format("{:.4g}", r.simulated) : "");
        if (r.group == "guideline") out << fmt::format("{:<10}   {}\n", "", r.note);
    }
    if (with_simulated) {
        out << "\nback-calculated coefficients of the simulated forces\n";
        for (const auto& k : c.coefficients)
            out << fmt::format("  {:<22} {:>10}   {}\n", k.name, range(k.value, k.value), k.definition);
    }
    out << fmt::format("\nbarrier typology: {}\n", c.typology);
    return out.str();
}

}  // namespace sabo::io
