// SPDX-License-Identifier: MIT
// The ghost planes of a slab whose lattice steps on an OpenCL device (lattice.device = "opencl" under
// mpirun; docs/scaling.md, "Slabs on devices"): the halo of parallel::LatticeHalo (fluid_halo.h) — as many
// ghost planes, refreshed as often, the elements' forces and the orphan mass summed over the ranks — with
// the planes' state staged through the host: packed on the device into one message per face, sent to the
// neighbour, unpacked on its device. Per refresh 2 × ghosts planes cross each way, O(ny nz) per rank.
#pragma once
#include <array>
#include <cstddef>
#include <span>
#include <stdexcept>
#include <vector>

#include "core/error.h"
#include "core/mpi_world.h"
#include "core/stopwatch.h"
#include "lbm/fluid_lattice.h"
#include "lbm/opencl/opencl_lattice.h"
#include "parallel/fluid_halo.h"
#include "parallel/slab_partition.h"

namespace sabo::parallel {

template <class Real>
class DeviceLatticeHalo final : public FluidHalo {
  public:
    // `device` steps `host`, of slab_shape(), which holds `slab` of the whole; both must outlive the halo.
    DeviceLatticeHalo(const MpiWorld& world, lbm::FluidLattice<Real>& host,
                      lbm::opencl::OpenClLattice<Real>& device, const LocalSlab& slab,
                      const HaloSettings& halo)
        : world_(world), slab_(slab), halo_(halo), device_(device) {
        if (halo.ghosts < 1 || halo.refresh_interval < 1 || slab.own_end - slab.own_begin < halo.ghosts)
            throw InputError(
                "slab lattice on a device: at least 1 ghost plane, a refresh every few steps and "
                "as many own planes as ghosts");
        if (host.own_begin() != slab.own_begin || host.own_end() != slab.own_end)
            throw std::logic_error("DeviceLatticeHalo: the lattice does not hold the slab");
        left_ = world.rank() > 0 ? world.rank() - 1 : -1;
        right_ = world.rank() + 1 < world.size() ? world.rank() + 1 : -1;
        for (std::vector<std::byte>& m : messages_) m.resize(device.packed_bytes(halo.ghosts));
        if (halo.free_surface)
            device.set_orphan_sum([this](double& mass, double& cells) {
                const ScopeSeconds timed(exchanging_);
                std::array<double, 2> sums{mass, cells};
                world_.sum_reals(sums);
                mass = sums[0];
                cells = sums[1];
            });
    }
    DeviceLatticeHalo(const DeviceLatticeHalo&) = delete;
    DeviceLatticeHalo& operator=(const DeviceLatticeHalo&) = delete;

    void prepare() override { refresh(); }
    void after_step() override {
        if (device_.steps() % static_cast<std::uint64_t>(halo_.refresh_interval) == 0) refresh();
        // each slab counted its own planes' links: the whole's forces are their sum
        exchanging_ += sum_forces_over_ranks(world_, device_.element_forces_to_sum(), force_sums_);
    }
    void refresh_whole() override {}  // (every refresh carries the ghost planes whole)
    [[nodiscard]] double exchange_seconds() const override { return exchanging_; }
    void add_exchange_seconds(double seconds) override { exchanging_ += seconds; }

  private:
    // The first own planes go left and the last right; the ghosts take the neighbours'.
    void refresh() {
        const ScopeSeconds timed(exchanging_);
        const int g = halo_.ghosts;
        auto& [to_left, to_right, from_left, from_right] = messages_;
        if (left_ >= 0) device_.pack_planes(slab_.own_begin, g, to_left);
        if (right_ >= 0) device_.pack_planes(slab_.own_end - g, g, to_right);
        device_.wait();
        world_.send_receive(to_left, left_, from_right, right_);
        world_.send_receive(to_right, right_, from_left, left_);
        if (left_ >= 0) device_.unpack_planes(slab_.own_begin - g, g, from_left);
        if (right_ >= 0) device_.unpack_planes(slab_.own_end, g, from_right);
    }

    const MpiWorld& world_;
    LocalSlab slab_;
    HaloSettings halo_;
    lbm::opencl::OpenClLattice<Real>& device_;
    int left_ = -1, right_ = -1;
    // to the left, to the right, from the left, from the right (the device reads the last two until the
    // next refresh's wait)
    std::array<std::vector<std::byte>, 4> messages_;
    std::vector<double> force_sums_;
    double exchanging_ = 0.0;
};

}  // namespace sabo::parallel
