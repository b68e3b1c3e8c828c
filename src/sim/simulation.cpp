// SPDX-License-Identifier: MIT
#include "sim/simulation.h"

#include <chrono>

namespace sabo::sim {

Simulation::Simulation(dem::DemSolver grains, Domain domain)
    : grains_(std::make_unique<dem::DemSolver>(std::move(grains))),
      clock_{grains_->dt(), grains_->steps()},
      domain_(std::move(domain)) {
    if (!domain_.divided()) return;
    grain_halo_ = std::make_unique<GrainHalo>(*domain_.world, *grains_, std::vector<double>{});
    grain_halo_->divide();  // last_forces_: summed after each step (observers read them after steps)
}

GrainView Simulation::grain_view() const {
    // one view per state: the observers of a sample and a frame share it (in a divided run one gather)
    if (!view_) view_.emplace(make_grain_view());
    return *view_;
}

GrainView Simulation::make_grain_view() const {
    if (grain_halo_) return assembly_.view(*domain_.world, *grains_, grain_halo_->total_grains());
    const dem::DemSolver& g = *grains_;
    return {g.time(),
            g.particles(),
            g.ids(),
            g.walls(),
            g.wall_forces(),
            g.stats(),
            g.elastic_energy(),
            g.max_overlap_ratio_seen(),
            g.list_builds()};
}

void Simulation::step(const std::function<void()>& after_grain_step) {
    // the solver that sets the clock counts its steps; the clock follows it even when the step throws
    // part-way (a RunError after the count was advanced)
    struct Follow {
        Simulation& sim;
        ~Follow() { sim.follow_solvers(); }
    } follow{*this};
    view_.reset();
    if (coupled()) {
        with_fluid([&](auto& l) {
            coupling_->before_fluid_step(grains_->particles(), l);
            l.step();
            coupling_->after_fluid_step(l, *grains_);
        });
        for (int k = 0; k < coupling_->settings().substeps; ++k) {
            grains_->step();
            view_.reset();
            if (after_grain_step) after_grain_step();
        }
    } else if (has_fluid()) {
        const auto start = std::chrono::steady_clock::now();
        const double exchanged = exchange_seconds();  // the step itself waits for the others' orphan mass
        with_fluid([](auto& l) { l.step(); });
        if (halo_) {
            stepping_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() -
                         (exchange_seconds() - exchanged);
            halo_->after_step();
            if (domain_.rebalance_every > 0 && lattice_steps() % domain_.rebalance_every == 0) rebalance();
        }
    } else if (grain_halo_) {
        const auto start = std::chrono::steady_clock::now();
        const double exchanged = exchange_seconds();
        grain_halo_->step();
        const auto stepped = std::chrono::steady_clock::now();
        stepping_ +=
            std::chrono::duration<double>(stepped - start).count() - (exchange_seconds() - exchanged);
        last_forces_ = assembly_.contact_forces(*domain_.world, *grains_, grain_halo_->total_grains());
        summing_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - stepped).count();
        if (after_grain_step) after_grain_step();
    } else {
        grains_->step();
        if (after_grain_step) after_grain_step();
    }
}

void Simulation::rebalance() {
    with_fluid([&](auto& l) {
        const auto start = std::chrono::steady_clock::now();
        const std::vector<int> cuts =
            rebalanced_cuts(*domain_.world, domain_.cuts, own_plane_costs(l), domain_.halo.ghosts);
        if (cuts != domain_.cuts) {
            move_faces(cuts, moved_lattice(*domain_.world, l, domain_.cuts, cuts, domain_.halo.ghosts));
            ++rebalances_;
        }
        halo_->add_exchange_seconds(
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    });
}

double Simulation::work_of_last_step() const {
    if (has_fluid()) return with_fluid([](const auto& l) { return static_cast<double>(l.updated_cells()); });
    return static_cast<double>(grains_->own_count());
}

}  // namespace sabo::sim
