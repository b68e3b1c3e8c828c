// SPDX-License-Identifier: MIT
// The grain cells found on the lattice's device (grain_cells.cl): the rules of coupling/grain_cells.h, the
// grains' centres and radii going up each step (O(grains)), the covered cells staying there as an owner per
// stored cell (the grain's index, or none) and, with partial saturation, the cell's solid fraction. What
// GrainCellFinder gives on the host, for a lattice that steps on a device.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "core/vec3.h"
#include "coupling/grain_cells.h"
#include "lbm/opencl/device_view.h"

namespace sabo::coupling::opencl {

class DeviceGrainCells {
  public:
    // Kernels built on the lattice's device for its shape; `stored_cells`: the lattice's stored cells.
    DeviceGrainCells(const lbm::opencl::DeviceView& view, std::size_t stored_cells, CoverRule rule);

    // The cells of the spheres of centres `x` and radii `r` in `frame` (the lattice's: its shape and
    // strides as the view's); the last call's cells are released first.
    void find(std::span<const Vec3> x, std::span<const double> r, const LatticeFrame& frame);
    // With a lattice built for solids: the cells found by the last find() covered for the next lattice step
    // (their share ε, and the grains' surface velocity v + ω × (x_c − x_p) there in lattice units: `v` m/s,
    // `w` rad/s, `dt` the lattice's step, s), and each grain's buoyancy weight Σ λ (ε − B) over its cells as
    // they are now (GrainFluidCoupling's). Grains in the order of find().
    void cover(std::span<const Vec3> v, std::span<const Vec3> w, double dt);
    // After the lattice step: each grain's F_h (the sum of its cells', lattice force units), its torque
    // Σ (x_c − x_p) × F_h (m times those), its cells and the buoyancy weight of cover(), summed in a fixed
    // order.
    struct GrainSums {
        std::vector<Vec3> force, torque;
        std::vector<double> buoyancy_weight;
        std::vector<double> cells;  // the grain's cells
    };
    // Enqueues the sums and their reading back (after the lattice's collision: they need nothing the free
    // surface's passes do); sums() then waits for them alone. sums() without it does both. (The sums are
    // the object's, valid until the next call: no allocation per step once they have the grains' size.)
    void request_sums();
    [[nodiscard]] const GrainSums& sums();
    // The cells found, ascending by cell, as GrainCellFinder::cells() (read back: for tests and checks).
    [[nodiscard]] std::vector<CoveredCell> read_cells(const LatticeFrame& frame) const;

  private:
    lbm::opencl::DeviceView view_;
    CoverRule rule_;
    std::size_t cells_ = 0;
    cl::Program program_;
    cl::Kernel claim_fraction_, claim_depth_, claim_grain_, release_, cover_, uncover_, forces_;
    cl::Buffer fraction_, depth_, owner_, x_, r_, v_, w_, weights_, sums_;
    // request_sums()' reading: the sums (7 per grain) and the read's end (the buoyancy weights are read
    // into sums_.buoyancy_weight, after them), and what sums() gives
    std::vector<double> sums_read_;
    cl::Event sums_ready_;
    GrainSums grain_sums_;
    bool sums_requested_ = false;
    bool covered_ = false;                   // the lattice's cells hold the last find()'s grains
    std::size_t grains_ = 0, capacity_ = 0;  // grains in x_, r_ (the last find's) and room for them
    int box_cells_ = 0;                      // the largest grain's box, cells
    Vec3 origin_{};
    double dx_ = 1.0;
    std::size_t group_ = 64;
    // Runs `kernel` over the grains now in x_, r_ (one work-group each) with the trailing buffers.
    void run(cl::Kernel& kernel);
};

}  // namespace sabo::coupling::opencl
