// SPDX-License-Identifier: MIT
#include "sim/simulation.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>

#include "core/error.h"

namespace sabo::sim {

Simulation::Simulation(dem::DemSolver grains, parallel::Domain domain)
    : grains_(std::make_unique<dem::DemSolver>(std::move(grains))),
      clock_{grains_->dt(), grains_->steps()},
      domain_(std::move(domain)) {
    if (!domain_.divided()) return;
    // faces where the grains' count is equal; a run fed from an empty channel: equal slabs of its length (the
    // faces then follow the grains that enter)
    std::vector<double> faces;
    if (grains_->particles().n_mobile == 0)
        for (int r = 1; r < domain_.world->size(); ++r)
            faces.push_back(domain_.box.x * r / domain_.world->size());
    grain_halo_ = std::make_unique<parallel::GrainHalo>(*domain_.world, *grains_, std::move(faces), true,
                                                        domain_.fed_radius_max);
    grain_halo_->divide();  // last_forces_: summed after each step (observers read them after steps)
}

dem::GrainView Simulation::grain_view() const {
    // one view per state: the observers of a sample and a frame share it (in a divided run one gather)
    if (!view_) view_.emplace(make_grain_view());
    return *view_;
}

void Simulation::run_fluid_on(const lbm::opencl::DeviceInfo& device) {
    if (!has_fluid() || (grains_ && !coupling_))
        throw InputError(
            "lattice.device = \"opencl\": the run has no lattice to step there: use lattice.device = "
            "\"cpu\"");
    // a divided run's ranks on one machine take its devices of that kind in turn (sharing their memory)
    device_info_ = domain_.divided() ? lbm::opencl::device_of_rank(device, domain_.world->local_rank(),
                                                                   domain_.world->local_size())
                                     : device;
    with_fluid([&](auto& l) { place_on_device(l); });
}

template <class Real>
void Simulation::place_on_device(lbm::FluidLattice<Real>& lattice) {
    // grains in the fluid: the lattice built for the cells they cover, which are found there too
    std::optional<lbm::SolidExchange> solids;
    if (coupling_)
        solids = coupling_->settings().model == coupling::CoverRule::psm ? lbm::SolidExchange::psm
                                                                         : lbm::SolidExchange::drag;
    std::unique_ptr<lbm::opencl::OpenClLattice<Real>> device;
    std::string refused;
    try {
        device = std::make_unique<lbm::opencl::OpenClLattice<Real>>(lattice, *device_info_, false, solids);
    } catch (const InputError& e) {
        if (!domain_.divided()) throw;
        refused = e.what();
    }
    // a slab that does not fit its device (or whose kernels fail there) stops every rank, before the ranks
    // wait for each other's ghost planes
    if (domain_.divided() && domain_.any(!refused.empty()))
        throw InputError(refused.empty() ? fmt::format("rank {}: another rank's lattice could not be placed "
                                                       "on its OpenCL device (its reason is in its log)",
                                                       domain_.world->rank())
                                         : refused);
    auto& d = *device;
    device_ = std::move(device);
    if (halo_) {  // a slab: its ghost planes through the host from now on
        const double exchanged = halo_->exchange_seconds();
        halo_ = std::make_unique<parallel::DeviceLatticeHalo<Real>>(*domain_.world, lattice, d, domain_.slab,
                                                                    domain_.halo);
        halo_->add_exchange_seconds(exchanged);
        // (the host lattice no longer steps: the orphan mass is the device's to sum)
        typename lbm::FluidLattice<Real>::SpreadOrphans never;
        if (domain_.halo.free_surface)
            never = [](std::vector<lbm::OrphanMass>&, std::uint64_t&) {
                throw std::logic_error("the host lattice of a device stepped");
            };
        lattice.set_slab({domain_.slab.own_begin, domain_.slab.own_end, domain_.slab.first_global_x, never});
        halo_->prepare();
    }
    make_device_cells();
    apply_region();
    host_behind_ = false;
}

void Simulation::make_device_cells() {
    device_cells_.reset();
    if (!coupling_) return;
    with_device([&](auto& d) {
        device_cells_ = std::make_unique<coupling::opencl::DeviceGrainCells>(
            d.view(), with_fluid([](const auto& l) { return l.cell_types().size(); }),
            coupling_->settings().model);
    });
}

void Simulation::pull_fluid() const {
    if (!host_behind_) return;
    with_device([](auto& d) { d.pull(); });
    host_behind_ = false;
}

void Simulation::push_fluid() {
    with_device([](auto& d) { d.push(); });
    // (the lattice's buffers are new: the grain cells' and the region's are made again)
    if (device_cells_) make_device_cells();
    apply_region();
    host_behind_ = false;
}

const lbm::FluidFields& Simulation::fluid_fields() const {
    const int own = with_fluid([](const auto& l) { return l.own_end() - l.own_begin(); });
    const bool whole = fields_fresh_ && fields_.nx == own;
    if (!whole) {
        // on a device: its fields, not its whole state
        const std::pair<int, int> own_planes = with_fluid([](const auto& l) {
            return std::pair{l.own_begin(), l.own_end()};
        });
        if (!with_device([&](auto& d) { d.snapshot(fields_, own_planes.first, own_planes.second); }))
            with_fluid([&](const auto& l) { l.snapshot(fields_); });
    }
    fields_fresh_ = true;
    return fields_;
}

const lbm::FluidFields& Simulation::fluid_fields(int x_begin, int x_end) const {
    if (!on_device()) return fluid_fields();
    // the own planes among them, in the lattice's local x
    int begin = 0, end = 0;
    with_fluid([&](const auto& l) {
        begin = std::clamp(x_begin - l.first_global_x(), l.own_begin(), l.own_end());
        end = std::clamp(x_end - l.first_global_x(), begin, l.own_end());
    });
    if (fields_fresh_ && fields_.first_x <= begin && end <= fields_.first_x + fields_.nx) return fields_;
    with_device([&](auto& d) { d.snapshot(fields_, begin, end); });
    fields_fresh_ = true;
    return fields_;
}

void Simulation::set_fluid_region(const std::function<std::uint8_t(const Vec3&)>& region) {
    region_ = region;
    apply_region();
    summary_.reset();
}

void Simulation::apply_region() {
    if (!region_ || !has_fluid()) return;
    // (every stored plane of a slab's: the device sums its own)
    with_fluid([&]<class Real>(lbm::FluidLattice<Real>& l) {
        const lbm::GridShape& shape = l.shape();
        std::vector<std::uint8_t> image(static_cast<std::size_t>(shape.nx) *
                                        static_cast<std::size_t>(shape.ny) *
                                        static_cast<std::size_t>(shape.nz));
        std::vector<std::uint8_t> stored(lbm::FluidLattice<Real>::stored_cells(shape), 0);
        for (int z = 0, c = 0; z < shape.nz; ++z)
            for (int y = 0; y < shape.ny; ++y)
                for (int x = 0; x < shape.nx; ++x, ++c) {
                    image[static_cast<std::size_t>(c)] = region_(domain_.cell_centre(x, y, z));
                    stored[l.index(x, y, z)] = image[static_cast<std::size_t>(c)];
                }
        l.set_region(std::move(stored));
        with_device([&](auto& d) { d.set_region(image); });
    });
}

const lbm::FluidSummary& Simulation::fluid_summary() const {
    if (summary_) return *summary_;
    if (!with_device([&](auto& d) { summary_ = d.summary(); }))
        with_fluid([&](const auto& l) {  // (the region's bits as the lattice holds them: apply_region())
            summary_ = lbm::summarize(fluid_fields(), [&](int x, int y, int z) {
                return l.region_bits(l.index(fields_.first_x + x, y, z));
            });
        });
    return *summary_;
}

std::span<const Vec3> Simulation::fluid_element_forces() const {
    std::span<const Vec3> forces;
    if (with_device([&](auto& d) { forces = d.element_forces(); })) return forces;
    return with_fluid([](const auto& l) { return std::span<const Vec3>(l.element_forces()); });
}

dem::GrainView Simulation::make_grain_view() const {
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

void Simulation::check_coupled_set_up(const Vec3& lattice_acceleration) const {
    const int n_sub = coupling_->settings().substeps;
    const double dem_dt = grains_->dt();
    if (std::abs(dem_dt * n_sub - clock_.dt) > 1e-9 * clock_.dt)
        throw InputError(
            fmt::format("grains in the fluid: the DEM step {:.6g} s x {} sub-steps = {:.6g} s must be "
                        "the lattice step {:.6g} s",
                        dem_dt, n_sub, dem_dt * n_sub, clock_.dt));
    const lbm::UnitConverter& units = coupling_->units();
    const Vec3 fluid = lattice_acceleration * units.acceleration_si(1.0), grains = grains_->gravity(),
               buoyancy = coupling_->settings().gravity;
    const double g = std::max({norm(fluid), norm(grains), norm(buoyancy)});
    const auto differ = [&](const Vec3& a, const Vec3& b) { return norm(a - b) > 1e-9 * g; };
    if (differ(fluid, grains) || differ(buoyancy, grains))
        throw InputError(fmt::format(
            "grains in the fluid: gravity must be one: the fluid's ({:.6g}, {:.6g}, {:.6g}), the grains' "
            "({:.6g}, {:.6g}, {:.6g}) and the buoyancy's ({:.6g}, {:.6g}, {:.6g}) m/s2",
            fluid.x, fluid.y, fluid.z, grains.x, grains.y, grains.z, buoyancy.x, buoyancy.y, buoyancy.z));
}

void Simulation::divide_grains_with_lattice() {
    grain_halo_ = std::make_unique<parallel::GrainHalo>(*domain_.world, *grains_, domain_.face_positions(),
                                                        false, domain_.fed_radius_max);
    grain_halo_->divide();
    visitors_ = std::make_unique<parallel::GrainVisitors>(*domain_.world);
    const int thinnest = thinnest_coupled_slab();
    for (std::size_t r = 1; r + 2 < domain_.cuts.size(); ++r)  // the first and last reach no third slab
        if (domain_.cuts[r + 1] - domain_.cuts[r] < thinnest)
            throw InputError(fmt::format(
                "{} MPI ranks: rank {}'s slab of the lattice is {} planes thick, fewer than the {} that "
                "grains "
                "in the fluid need ({} ghost planes and the grains' contact reach of {:.4g} m); use at most "
                "{} "
                "ranks",
                domain_.ranks(), r, domain_.cuts[r + 1] - domain_.cuts[r], thinnest, domain_.halo.ghosts,
                grain_halo_->ghost_reach(), std::max(2, domain_.cuts.back() / thinnest)));
}

void Simulation::remove_grains(const std::function<bool(const Vec3&)>& leaves) {
    const dem::Particles& p = grains_->particles();
    const std::size_t n = grain_halo_ ? grains_->own_count() : p.n_mobile;
    leaving_.assign(n, 0);
    for (std::size_t i = 0; i < n; ++i) leaving_[i] = leaves(p.x[i]) ? 1 : 0;
    if (grain_halo_)
        grain_halo_->remove(leaving_);
    else
        grains_->remove_mobile(leaving_);
    view_.reset();
}

void Simulation::triangle_forces(const geometry::TriangleMesh& mesh, std::vector<Vec3>& out) const {
    out.assign(mesh.triangles.size(), Vec3{});
    grains_->add_triangle_forces(mesh, out);
    std::vector<double> scratch;
    if (grain_halo_) domain_.world->sum_vectors(out, scratch);
}

void Simulation::fluid_triangle_forces(const geometry::TriangleMesh& mesh,
                                       std::span<const std::size_t> element_part,
                                       std::vector<Vec3>& out) const {
    out.assign(mesh.triangles.size(), Vec3{});
    with_fluid([&](const auto& l) {
        const lbm::BarrierLinks& links = l.barrier_links();
        std::span<const double> momentum = links.momentum;
        with_device([&](auto& d) { momentum = d.barrier_link_momenta(); });
        const auto centre = [&](std::uint32_t k) {
            const auto c = l.coords(k);
            return domain_.cell_centre(c[0], c[1], c[2]);  // (a slab's local x)
        };
        const std::span<const std::uint32_t> triangle =
            link_triangles_.of(links, mesh, element_part, centre, domain_.dx);
        for (std::size_t j = 0; j < links.size(); ++j) {
            const int i = links.direction[j];
            const double m = momentum[j];
            out[triangle[j]] += Vec3{lbm::cx[i] * m, lbm::cy[i] * m, lbm::cz[i] * m};
        }
    });
    std::vector<double> scratch;
    if (domain_.divided()) domain_.world->sum_vectors(out, scratch);
}

void Simulation::add_grains(std::vector<dem::GrainRecord> grains) {
    if (grain_halo_) {
        grain_halo_->add(std::move(grains));  // (collective: every rank the same batch)
    } else {
        grains_->add_mobile(std::move(grains));
    }
    view_.reset();
}

double Simulation::exchange_seconds() const {
    return (halo_ ? halo_->exchange_seconds() : 0.0) + grain_exchange_seconds() + face_moving_;
}

double Simulation::grain_exchange_seconds() const {
    double seconds = 0.0;
    // (the grain halo's face moves happen in rebalance(): counted in face_moving_)
    if (grain_halo_)
        seconds +=
            grain_halo_->exchange_seconds() + grain_halo_->repartition_seconds() - grains_moved_ + summing_;
    if (visitors_) seconds += visitors_->exchange_seconds();
    return seconds;
}

void Simulation::step(const std::function<void()>& after_grain_step) {
    // the solver that sets the clock counts its steps; the clock follows it even when the step throws
    // part-way (a RunError after the count was advanced)
    struct Follow {
        Simulation& sim;
        ~Follow() { sim.follow_solvers(); }
    } follow{*this};
    state_changed();
    if (has_fluid()) {
        // the faces move between steps, before the grains' cells are found: through a step the lattice and
        // the grains' ownership agree, and the observers read the lattice as it was stepped
        const std::uint64_t done = lattice_steps();
        if (halo_ && domain_.rebalance_every > 0 && done % domain_.rebalance_every == 0) {
            // the first slabs were cut equal, before the fill and the grains were known: before the first
            // step the faces go where the set-up's work is, in as many moves as that takes (a face moves at
            // most to its neighbours' old ones)
            if (done == 0)
                for (int move = 1; move < domain_.ranks() && rebalance(); ++move) {
                }
            else
                rebalance();
        }
        // a grain that passed through a wall (or blew up) in the last sub-steps is refused before the
        // lattice is given its cells, whoever steps the simulation (O(grains))
        if (coupled()) check_state();
        with_fluid([&](auto& l) {
            if (coupled())
                exchange_with_fluid(l);
            else
                timed(Phase::lattice, [&] { step_lattice(l); });
        });
        if (coupled())
            timed(Phase::grains, [&] {
                for (int k = 0; k < coupling_->settings().substeps; ++k) step_grains(after_grain_step);
            });
    } else {
        timed(Phase::grains, [&] { step_grains(after_grain_step); });
    }
}

void Simulation::step_grains(const std::function<void()>& after_grain_step) {
    view_.reset();
    if (grain_halo_) {
        const auto start = std::chrono::steady_clock::now();
        const double exchanged = exchange_seconds();
        grain_halo_->step();
        const auto stepped = std::chrono::steady_clock::now();
        stepping_ +=
            std::chrono::duration<double>(stepped - start).count() - (exchange_seconds() - exchanged);
        last_forces_ = assembly_.contact_forces(*domain_.world, *grains_, grain_halo_->total_grains());
        summing_ += seconds_since(stepped);
    } else {
        grains_->step();
    }
    if (after_grain_step) after_grain_step();
}

bool Simulation::rebalance() {
    pull_fluid();  // (a lattice on a device: its state moves with the faces, then goes back up)
    bool moved = false;
    with_fluid([&](auto& l) {
        const auto start = std::chrono::steady_clock::now();
        std::vector<double> costs = parallel::own_plane_costs(l);
        int thin = 2 * domain_.halo.ghosts;
        if (grain_halo_) {  // the grains' steps too, and slabs no thinner than their contacts' reach
            const double per_grain = parallel::PlaneCostWeights{}.grain * coupling_->settings().substeps;
            parallel::add_grain_costs(costs, l, grains_->particles().x, grains_->own_count(),
                                      domain_.origin.x + l.first_global_x() * domain_.dx, domain_.dx,
                                      per_grain);
            thin = std::max(thin, thinnest_coupled_slab());
        }
        const std::vector<int> cuts = parallel::rebalanced_cuts(*domain_.world, domain_.cuts, costs, thin);
        moved = cuts != domain_.cuts;
        if (moved) {
            halo_->refresh_whole();
            using Lattice = std::remove_cvref_t<decltype(l)>;
            std::unique_ptr<Lattice> spare;
            if (auto* kept = std::get_if<std::unique_ptr<Lattice>>(&spare_fluid_)) spare = std::move(*kept);
            move_faces(cuts, parallel::moved_lattice(*domain_.world, l, domain_.cuts, cuts,
                                                     domain_.halo.ghosts, std::move(spare)));
            ++rebalances_;
            if (grain_halo_) {
                const double repartitioned = grain_halo_->repartition_seconds();
                grain_halo_->move_faces(domain_.face_positions());
                grains_moved_ += grain_halo_->repartition_seconds() - repartitioned;
            }
        }
        face_moving_ += seconds_since(start);
    });
    return moved;
}

double Simulation::work_of_last_step() const {
    double updated = 0.0;
    if (with_device([&](auto& d) { updated = static_cast<double>(d.updated_cells()); })) return updated;
    if (has_fluid()) return with_fluid([](const auto& l) { return static_cast<double>(l.updated_cells()); });
    return static_cast<double>(grains_->own_count());
}

template void Simulation::place_on_device(lbm::FluidLattice<float>&);
template void Simulation::place_on_device(lbm::FluidLattice<double>&);

}  // namespace sabo::sim
