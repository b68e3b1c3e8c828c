// SPDX-License-Identifier: MIT
#include "sim/run_rates.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <toml++/toml.h>

#include <cmath>
#include <cstdlib>
#include <sstream>

#include "io/atomic_file.h"
#include "sim/run_control.h"

namespace sabo::sim {

namespace {

// Grains alone on the 2-core reference machine (AMD Zen 5, the README's slit run): 1.5e7 particle-steps/s on
// 2 threads. Only a first guess: dense deposits, many walls or a barrier mesh change it.
constexpr double reference_particle_steps_per_thread = 7.5e6;

// A rate's key: the kind of run, then the thread count ("debris/coupled/cpu/threads=2").
std::string key_prefix(const RunWork& work) {
    return work.kind + "/threads=";
}

std::string rate_key(const RunWork& work, int threads) {
    return key_prefix(work) + std::to_string(threads);
}

toml::table read_rates(const std::filesystem::path& file) {
    try {
        return std::filesystem::exists(file) ? toml::parse_file(file.string()) : toml::table{};
    } catch (const std::exception& e) {  // a damaged file is replaced by the next record
        spdlog::debug("{}: not read ({})", file.string(), e.what());
        return {};
    }
}

}  // namespace

RunWork run_work(const Config& cfg) {
    RunWork w;
    std::string type = cfg.recorded_text("case.type");
    if (type.empty()) type = "channel";  // the default case type
    const double nodes = cfg.recorded_number("derived.lattice_nodes");
    const double grains =
        std::max(cfg.recorded_number("derived.particles"), cfg.recorded_number("derived.grains"));
    std::string holds = cfg.recorded_text("derived.mode");  // the debris case: fluid, coupled or dry
    if (holds.empty()) holds = nodes > 0.0 ? (grains > 0.0 ? "coupled" : "fluid") : "grains";
    const bool opencl = nodes > 0.0 && cfg.recorded_text("lattice.device") == "opencl";
    w.kind = fmt::format("{}/{}/{}", type, holds, opencl ? "opencl" : "cpu");
    if (nodes > 0.0) {
        w.unit = "node-steps";
        w.per_step = nodes;
        w.step_s = cfg.recorded_number("lattice.dt_s");
    } else {
        w.unit = "particle-steps";
        w.per_step = grains;
        w.step_s = cfg.recorded_number("derived.dt_s");  // the DEM's
    }
    return w;
}

std::filesystem::path rates_file() {
    if (const char* f = std::getenv("SABO_RATES_FILE"); f != nullptr && *f != '\0') return f;
    if (const char* c = std::getenv("XDG_CACHE_HOME"); c != nullptr && *c != '\0')
        return std::filesystem::path(c) / "sabo" / "rates.toml";
    if (const char* h = std::getenv("HOME"); h != nullptr && *h != '\0')
        return std::filesystem::path(h) / ".cache" / "sabo" / "rates.toml";
    return {};
}

void record_rate(const RunWork& work, int threads, double work_per_s) {
    const std::filesystem::path file = rates_file();
    if (file.empty() || !(work_per_s > 0.0) || !std::isfinite(work_per_s)) return;
    try {
        toml::table rates = read_rates(file);
        rates.insert_or_assign(rate_key(work, threads), work_per_s);
        std::filesystem::create_directories(file.parent_path());
        std::ostringstream text;
        text << "# sabo: this machine's speed per kind of run and thread count (work per wall second)\n"
             << rates << '\n';
        io::write_text_atomically(file, text.str());
    } catch (const std::exception& e) {
        spdlog::debug("this run's speed was not kept in {}: {}", file.string(), e.what());
    }
}

std::string wall_time_estimate(const RunWork& work, double simulated_s, int threads, bool may_stop_early) {
    if (!(work.step_s > 0.0) || !(work.per_step > 0.0) || !(simulated_s > 0.0)) return {};
    const double total = work.per_step * std::ceil(simulated_s / work.step_s);
    const std::filesystem::path file = rates_file();
    const toml::table rates = file.empty() ? toml::table{} : read_rates(file);
    double rate = 0.0;
    std::string source;
    if (const auto same = rates[rate_key(work, threads)].value<double>()) {
        rate = *same;
        source = fmt::format("this machine's last {} run on {} threads", work.kind, threads);
    } else {
        // the nearest thread count measured, scaled by the thread ratio (optimistic upwards)
        int nearest = 0;
        const std::string prefix = key_prefix(work);
        for (const auto& [key, value] : rates) {
            const std::string k(key.str());
            if (k.rfind(prefix, 0) != 0 || !value.is_number()) continue;
            const int t = std::atoi(k.c_str() + prefix.size());
            if (t > 0 && (nearest == 0 || std::abs(t - threads) < std::abs(nearest - threads))) {
                nearest = t;
                rate = value.value_or(0.0) * static_cast<double>(threads) / t;
            }
        }
        if (nearest > 0)
            source = fmt::format("this machine's last {} run on {} threads, scaled to {}", work.kind, nearest,
                                 threads);
    }
    if (rate <= 0.0 && work.unit == "particle-steps") {
        rate = reference_particle_steps_per_thread * threads;
        source = fmt::format(
            "a 2-core reference machine's {:.2g} particle-steps/s per thread: no run of this "
            "kind here yet",
            reference_particle_steps_per_thread);
    }
    if (rate <= 0.0)
        return fmt::format(
            "wall time: no estimate yet — no {} run on this machine so far; a short one "
            "(--set case.end_time_s=...) gives `sabo check` this machine's speed ({})",
            work.kind, file.string());
    return fmt::format(
        "wall time: {}about {} for {:.3g} {} at {:.3g}/s (an estimate, from {}; speeds kept in {})",
        may_stop_early ? "at most " : "", format_duration(total / rate), total, work.unit, rate, source,
        file.string());
}

}  // namespace sabo::sim
