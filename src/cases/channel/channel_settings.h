// SPDX-License-Identifier: MIT
// A channel case's keys read and checked (scenario, contact model, analyses, outputs) and its derived
// numbers (`sabo check`).
#pragma once
#include "cases/common/gauge_settings.h"
#include "core/config.h"
#include "dem/dem_setup.h"
#include "scenario/channel_case.h"
#include "sim/case_settings.h"

namespace sabo::cases {

// The [analysis] and [stop] keys of a channel case.
struct AnalysisSettings {
    double arching_depth = 0.0;  // m (4 r)
    int arching_intervals = 10;
    double arching_threshold = 1e-5;  // J
    double upstream_reach = 1.0;      // m, reach for h and v of k_st, k_dyn
    GaugeSettings gauge;
    bool stop_enabled = true;
    double stop_threshold = 0.0;   // J, total kinetic energy
    double stop_hold = 1.0;        // s
    double stop_not_before = 0.0;  // s: an inflow's end (no complete stop while grains still come)
};

// A channel case read and checked.
struct PreparedCase {
    scenario::ChannelCase scene;
    dem::DemSettings dem;
    AnalysisSettings analysis;
    sim::OutputSettings output;
};

[[nodiscard]] PreparedCase prepare_channel(const sim::RunRequest& req, const Config& cfg);
void print_derived(const PreparedCase& pc);

}  // namespace sabo::cases
