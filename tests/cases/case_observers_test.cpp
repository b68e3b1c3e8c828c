// SPDX-License-Identifier: MIT
// The observers of the sandpile and the dam break, driven by hand on their case types' own simulations
// (tiny versions of the shipped cases): the sandpile's phases and gates, the dam break's front and its
// scaling; and the registry that maps case.type to a case type.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "cases/channel/channel_type.h"
#include "cases/dam_break/dam_break_type.h"
#include "cases/registry.h"
#include "cases/sandpile/sandpile_type.h"
#include "core/error.h"

namespace sabo {
namespace {

std::filesystem::path scratch(const std::string& name) {
    const auto dir = std::filesystem::temp_directory_path() / ("sabo_case_observers_" + name);
    std::filesystem::remove_all(dir);
    return dir;
}

Config shipped(const char* file, std::vector<std::string> overrides) {
    overrides.push_back("output.report=false");
    return Config::from_file(std::filesystem::path(SABO_SOURCE_DIR) / "cases" / file, overrides);
}

// A case type's simulation and observers, as `sabo run` builds them, not run.
struct Built {
    Built(const char* file, std::vector<std::string> overrides, const std::string& name)
        : cfg(shipped(file, std::move(overrides))), type(cases::make_case_type(cfg)) {
        type->prepare({file, scratch(name), false}, cfg);
        std::filesystem::create_directories(type->output().out_dir);
        sim.emplace(std::move(*type->build(type->domain(nullptr), control, false)));
        observers = type->observers(*sim);
    }
    Config cfg;
    std::unique_ptr<sim::CaseType> type;
    sim::RunControl control{1e9, 0};
    std::optional<sim::Simulation> sim;
    std::vector<sim::Observer*> observers;
};

TEST(SandpileObserver, OpensTheGatesAtTheLatestSettlingTimeAndNotBefore) {
    Built run("sandpile.toml",
              {"sandpile.particles=200", "sandpile.width_over_d=6", "sandpile.plate_length_over_d=8",
               "sandpile.settle_max_time_s=0.002"},
              "gates");
    auto& sandpile = *dynamic_cast<cases::SandpileObserver*>(run.observers.at(1));
    sim::Simulation& s = *run.sim;
    const auto gates_open = [&] {
        for (const auto& w : s.grains().walls())
            if (!w.active) return true;
        return false;
    };
    const auto settle_steps = static_cast<std::uint64_t>(std::ceil(0.002 / s.dt() - 1e-9));
    ASSERT_GT(settle_steps, 2u);
    EXPECT_FALSE(sandpile.sample(s));  // the first row, before any step, never ends the run
    while (s.steps() < settle_steps) {
        sandpile.before_step(s);
        EXPECT_FALSE(sandpile.draining()) << "opened early, at step " << s.steps();
        EXPECT_EQ(sandpile.phase(), "settling");
        s.step();
    }
    EXPECT_FALSE(gates_open());
    sandpile.before_step(s);  // the step at settle_max_time_s
    EXPECT_TRUE(sandpile.draining());
    EXPECT_EQ(sandpile.phase(), "draining");
    EXPECT_TRUE(gates_open());
    EXPECT_DOUBLE_EQ(sandpile.opened_at(), s.time());
    EXPECT_LT(sandpile.stopped_at(), 0.0);  // not stopped
}

TEST(DamBreakObserver, TheFrontStartsAtTheColumnAndAdvancesOnTheScaledClock) {
    Built run("dam_break.toml", {"lattice.dx_m=0.0047625", "lattice.dt_s=2.25e-4", "case.end_time_s=0.05"},
              "front");
    auto& front = *dynamic_cast<cases::DamBreakObserver*>(run.observers.at(0));
    sim::Simulation& s = *run.sim;
    EXPECT_FALSE(front.sample(s));
    ASSERT_EQ(front.fronts().size(), 1u);
    EXPECT_DOUBLE_EQ(front.fronts()[0], 1.0);  // x / a: the column's face, before any step
    EXPECT_DOUBLE_EQ(front.times()[0], 0.0);
    EXPECT_EQ(front.worst_drift(), 0.0);
    for (int k = 0; k < 120; ++k) s.step();
    EXPECT_FALSE(front.sample(s));
    ASSERT_EQ(front.fronts().size(), 2u);
    EXPECT_GT(front.fronts()[1], 1.0);  // the surge has left the column
    // T = t sqrt(2 g / a), a the column's width in whole cells
    const double a = static_cast<double>(std::lround(0.05715 / 0.0047625)) * 0.0047625;
    EXPECT_NEAR(front.times()[1], s.time() * std::sqrt(2.0 * 9.81 / a), 1e-9);
    EXPECT_LT(front.worst_drift(), 1e-6);
}

TEST(CaseRegistry, NamesEveryTypeAndRefusesAnother) {
    const auto names = cases::case_type_names();
    EXPECT_EQ(names, (std::vector<std::string_view>{"channel", "sandpile", "dam_break", "debris"}));
    const Config other = Config::from_string("[case]\ntype = \"avalanche\"\n", "other.toml");
    try {
        (void)cases::make_case_type(other);
        FAIL() << "an unknown case.type was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("case.type"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("dam_break"), std::string::npos) << e.what();
    }
    const Config none = Config::from_string("[case]\nname = \"x\"\n", "none.toml");
    EXPECT_NE(dynamic_cast<cases::ChannelType*>(cases::make_case_type(none).get()), nullptr);
}

}  // namespace
}  // namespace sabo
