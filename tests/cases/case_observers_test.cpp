// SPDX-License-Identifier: MIT
// Each case type's observer, driven by hand on its case type's own simulation (tiny versions of the shipped
// cases): the channel's non-retained fraction, the debris run's fluid forces on the barrier and its
// retained block, the sandpile's phases and gates, the dam break's front and its scaling; and the registry
// that maps case.type to a case type.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "cases/channel/channel_type.h"
#include "cases/dam_break/dam_break_type.h"
#include "cases/debris/debris_type.h"
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

TEST(ChannelObserver, CountsTheMassOfAGrainPastTheBarrierAsNonRetained) {
    Built run("slit_barrier.toml", {"release.solid_volume_m3=0.02", "case.end_time_s=1"}, "channel");
    auto& analysis = *dynamic_cast<cases::ChannelObserver*>(run.observers.at(0));
    sim::Simulation& s = *run.sim;
    EXPECT_FALSE(analysis.sample(s));
    EXPECT_EQ(analysis.non_retained(), 0.0);  // the whole block upstream
    // one grain carried past the barrier's downstream face, at its height
    dem::Particles& p = s.grains().particles();
    ASSERT_GT(p.n_mobile, 10u);
    double total = 0.0;
    for (std::size_t i = 0; i < p.n_mobile; ++i) total += p.m[i];
    const double moved = p.m[3];
    p.x[3].x += 30.0 * p.r[3] + 12.0;  // beyond the barrier (face at 8 m less than 12 m from the block)
    s.grains().refresh();
    s.step();  // a new state (the grains may be reordered): the observers' view of them is made anew
    analysis.sample(s);
    EXPECT_NEAR(analysis.non_retained(), moved / total, 1e-12);
}

TEST(DebrisObserver, RecordsTheFluidsForceOnEveryElementAndStartsRetained) {
    Built run("debris_fluid.toml",
              {"channel.width_m=0.4", "channel.length_m=2", "channel.height_m=0.6",
               "debris.block_length_m=0.6", "debris.block_height_m=0.4", "lattice.dx_m=0.05",
               "barrier.face_x_m=1.2", "case.end_time_s=1", "debris.solid_fraction=0"},
              "debris");
    auto& debris = *dynamic_cast<cases::DebrisObserver*>(run.observers.at(0));
    sim::Simulation& s = *run.sim;
    EXPECT_FALSE(debris.sample(s));
    EXPECT_EQ(debris.state().non_retained, 0.0);  // the block upstream of the barrier
    EXPECT_EQ(debris.state().worst_drift, 0.0);
    EXPECT_EQ(debris.state().m0, s.fluid_fields().totals.mass);
    const double force_unit = dynamic_cast<cases::DebrisType&>(*run.type).fluid_units().force_si(1.0);
    double largest = 0.0;
    for (int k = 0; k < 800; ++k) {
        s.step();
        debris.after_step(s);
        Vec3 sum{};
        const auto f = s.fluid_element_forces();
        for (std::size_t e = 1; e < f.size(); ++e) sum += f[e] * force_unit;
        EXPECT_NEAR(norm(debris.forces().fluid_global() - sum), 0.0, 1e-9 * (1.0 + norm(sum)))
            << "step " << k;
        largest = std::max(largest, debris.forces().fluid_normal());
    }
    EXPECT_GT(largest, 0.0) << "the fluid never reached the barrier";
    EXPECT_DOUBLE_EQ(debris.forces().max_fluid_normal(), largest);
    // the windowed means: a longer window is an average of shorter ones, each no more than the largest step
    const auto& means = debris.normal_means();
    EXPECT_GT(means[2].max_mean(), 0.0);
    EXPECT_LE(means[0].max_mean(), debris.forces().max_normal() * (1.0 + 1e-12));
    EXPECT_LE(means[1].max_mean(), means[0].max_mean() * (1.0 + 1e-12));
    EXPECT_LE(means[2].max_mean(), means[1].max_mean() * (1.0 + 1e-12));
}

// The run-up against a closed barrier: a top just above the block is reached — a lid turns it back and
// nothing leaves, an open top lets it out and counts it — and a tall open domain is not; the highest fluid
// is recorded either way.
TEST(DebrisObserver, SaysWhenTheRunUpReachesTheDomainsTop) {
    const auto run_up = [](std::vector<std::string> top) {
        std::vector<std::string> keys{
            "channel.width_m=0.4",       "channel.length_m=1.6",      "channel.height_m=0.5",
            "debris.block_length_m=0.6", "debris.block_height_m=0.4", "lattice.dx_m=0.05",
            "barrier.face_x_m=1.2",      "barrier.type=closed",       "barrier.height_m=0.5",
            "case.end_time_s=1",         "debris.solid_fraction=0"};
        keys.insert(keys.end(), top.begin(), top.end());
        Built run("debris_fluid.toml", keys, "run_up");
        auto& debris = *dynamic_cast<cases::DebrisObserver*>(run.observers.at(0));
        sim::Simulation& s = *run.sim;
        for (int k = 0; k < 1600; ++k) {
            s.step();
            if (k % 20 == 0) (void)debris.sample(s);
        }
        return debris.state();
    };
    const auto lid = run_up({"channel.top=lid", "channel.height_m=0.55", "barrier.height_m=0.5"});
    EXPECT_TRUE(lid.top_reached);
    EXPECT_DOUBLE_EQ(lid.max_height, 0.55);
    EXPECT_EQ(lid.left[0] + lid.left[1] + lid.left[2], 0.0);
    // (the top is reached when a tenth of a cell's fluid stands in the plane below the outlet's)
    const auto open_low = run_up({"channel.domain_height_m=0.65"});
    EXPECT_TRUE(open_low.top_reached);
    EXPECT_GE(open_low.max_height, 0.6 - 1e-12);
    EXPECT_LE(open_low.max_height, 0.65 + 1e-12);
    EXPECT_GT(open_low.left[2], 0.0) << "the run-up leaves through the open top";
    const auto tall = run_up({"channel.domain_height_m=3.0"});
    EXPECT_FALSE(tall.top_reached);
    EXPECT_GT(tall.max_height, 0.5) << "the run-up climbs above the barrier's crest";
    EXPECT_LT(tall.max_height, 3.0);
    EXPECT_EQ(tall.left[2], 0.0);
}

// Under a lid, an open end lets the fluid out at the channel's end and nowhere else; a closed box keeps it.
TEST(DebrisObserver, AnOpenEndUnderALidLetsTheFluidOutAtTheEndOnly) {
    const auto left = [](std::string end) {
        Built run("debris_fluid.toml",
                  {"channel.width_m=0.4", "channel.length_m=1.6", "channel.height_m=0.5", "channel.top=lid",
                   "channel.end=" + end, "debris.block_length_m=0.6", "debris.block_height_m=0.4",
                   "lattice.dx_m=0.05", "barrier.type=none", "barrier.face_x_m=1.2", "case.end_time_s=1",
                   "debris.solid_fraction=0"},
                  "open_end_" + end);
        auto& debris = *dynamic_cast<cases::DebrisObserver*>(run.observers.at(0));
        sim::Simulation& s = *run.sim;
        for (int k = 0; k < 1600; ++k) {
            s.step();
            if (k % 20 == 0) (void)debris.sample(s);
        }
        return debris.state().left;
    };
    const auto open = left("open");
    EXPECT_GT(open[0], 0.1) << "the fluid leaves at the end";
    EXPECT_EQ(open[1] + open[2], 0.0) << "not over the walls nor through the lid";
    const auto wall = left("wall");
    EXPECT_EQ(wall[0] + wall[1] + wall[2], 0.0);
}

// An open channel's side walls are as high as the walls: a grain that went over one has left the channel;
// the run removes it and counts its mass, which then counts in the whole of the non-retained fraction. A
// grain past an open end has left too, and passed. The counts are the ranks' sums at the next series row.
TEST(DebrisObserver, RemovesAndCountsTheGrainsThatGoOverTheSideWallsOrPastTheEnd) {
    Built run("debris_fluid.toml",
              {"channel.width_m=0.6", "channel.length_m=12", "lattice.dx_m=0.05", "release.radius_mean_m=0.1",
               "debris.solid_fraction=0.2", "debris.dry=true", "case.end_time_s=1", "channel.end=open"},
              "spill");
    auto& debris = *dynamic_cast<cases::DebrisObserver*>(run.observers.at(0));
    sim::Simulation& s = *run.sim;
    dem::Particles& p = s.grains().particles();
    const std::size_t before = p.n_mobile;
    const double m0 = p.m[0], m1 = p.m[1];
    debris.after_step(s);  // every grain inside: nothing happens
    ASSERT_EQ(s.grains().particles().n_mobile, before);
    p.x[0] = {3.0, -0.02, 1.5};  // over the wall at y = 0 (1.35 m high)
    p.x[1] = {12.01, 0.3, 0.2};  // past the open end at x = 12 m
    debris.after_step(s);
    s.step();  // the solver drops removed grains at its next step
    EXPECT_EQ(s.grains().particles().n_mobile, before - 2);
    EXPECT_EQ(debris.outflow().spilled_grains(), 0.0) << "counted at the next row";
    (void)debris.sample(s);
    EXPECT_EQ(debris.outflow().spilled_grains(), 1.0);
    EXPECT_DOUBLE_EQ(debris.outflow().spilled_mass_kg(), m0);
    EXPECT_EQ(debris.outflow().left_end_grains(), 1.0);
    EXPECT_DOUBLE_EQ(debris.outflow().left_end_mass_kg(), m1);
    // the side walls are slabs of the walls' height, not planes as high as the domain
    const auto& walls = s.grains().walls();
    const auto side =
        std::find_if(walls.begin(), walls.end(), [](const dem::Wall& w) { return w.name == "side_y0"; });
    ASSERT_NE(side, walls.end());
    EXPECT_EQ(side->shape, dem::WallShape::box);
    EXPECT_DOUBLE_EQ(side->point.z + side->half.z, 1.35);
}

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
    EXPECT_EQ(names,
              (std::vector<std::string_view>{"channel", "sandpile", "dam_break", "debris", "fluid_box"}));
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
