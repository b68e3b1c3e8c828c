// SPDX-License-Identifier: MIT
#include "coupling/opencl/device_grain_cells.h"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

#include "core/error.h"
#include "sabo/coupling_kernels.h"

namespace sabo::coupling::opencl {

namespace {

constexpr std::uint64_t unclaimed_depth = ~std::uint64_t{0};
constexpr std::uint32_t no_grain = ~std::uint32_t{0};
constexpr double half_diagonal = 0.86602540378443865;

}  // namespace

DeviceGrainCells::DeviceGrainCells(const lbm::opencl::DeviceView& view, std::size_t stored_cells,
                                   CoverRule rule)
    : view_(view), rule_(rule), cells_(stored_cells) {
    try {
        program_ = cl::Program(view_.context, std::string(coupling_kernels::grain_cells));
        const std::string options =
            view_.options + fmt::format(" -D PSM={}", rule_ == CoverRule::psm ? 1 : 0);
        try {
            program_.build({view_.device}, options.c_str());
        } catch (const cl::Error&) {
            throw InputError(fmt::format("the grain cells' kernels did not build on the OpenCL device:\n{}",
                                         program_.getBuildInfo<CL_PROGRAM_BUILD_LOG>(view_.device)));
        }
        claim_fraction_ = cl::Kernel(program_, "claim_fraction");
        claim_depth_ = cl::Kernel(program_, "claim_depth");
        claim_grain_ = cl::Kernel(program_, "claim_grain");
        release_ = cl::Kernel(program_, "release");
        if (view_.solids) {
            cover_ = cl::Kernel(program_, "cover_cells");
            uncover_ = cl::Kernel(program_, "uncover_cells");
            forces_ = cl::Kernel(program_, "grain_forces");
        }
        group_ = std::min<std::size_t>(64, view_.device.getInfo<CL_DEVICE_MAX_WORK_GROUP_SIZE>());
        fraction_ = cl::Buffer(view_.context, CL_MEM_READ_WRITE, cells_ * sizeof(std::uint64_t));
        depth_ = cl::Buffer(view_.context, CL_MEM_READ_WRITE, cells_ * sizeof(std::uint64_t));
        owner_ = cl::Buffer(view_.context, CL_MEM_READ_WRITE, cells_ * sizeof(std::uint32_t));
        view_.queue.enqueueFillBuffer(fraction_, std::uint64_t{0}, 0, cells_ * sizeof(std::uint64_t));
        view_.queue.enqueueFillBuffer(depth_, unclaimed_depth, 0, cells_ * sizeof(std::uint64_t));
        view_.queue.enqueueFillBuffer(owner_, no_grain, 0, cells_ * sizeof(std::uint32_t));
        claim_fraction_.setArg(7, fraction_);
        claim_depth_.setArg(7, fraction_);
        claim_depth_.setArg(8, depth_);
        for (cl::Kernel* k : {&claim_grain_, &release_}) {
            k->setArg(7, fraction_);
            k->setArg(8, depth_);
            k->setArg(9, owner_);
        }
        if (view_.solids) {
            uncover_.setArg(7, owner_);
            uncover_.setArg(8, view_.solid_fraction);
        }
    } catch (const cl::Error& e) {
        throw InputError(
            fmt::format("the grain cells on the OpenCL device: {} (error {})", e.what(), e.err()));
    }
}

void DeviceGrainCells::run(cl::Kernel& kernel) {
    if (grains_ == 0) return;
    kernel.setArg(0, box_cells_);
    kernel.setArg(1, x_);
    kernel.setArg(2, r_);
    kernel.setArg(3, origin_.x);
    kernel.setArg(4, origin_.y);
    kernel.setArg(5, origin_.z);
    kernel.setArg(6, dx_);
    view_.queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(grains_ * group_),
                                     cl::NDRange(group_));
}

void DeviceGrainCells::find(std::span<const Vec3> x, std::span<const double> r, const LatticeFrame& frame) {
    try {
        if (covered_) run(uncover_);  // the last call's grains, where they were
        covered_ = false;
        run(release_);
        grains_ = x.size();
        if (grains_ > capacity_) {
            capacity_ = std::max<std::size_t>(grains_, 2 * capacity_);
            x_ = cl::Buffer(view_.context, CL_MEM_READ_ONLY, 3 * capacity_ * sizeof(double));
            r_ = cl::Buffer(view_.context, CL_MEM_READ_ONLY, capacity_ * sizeof(double));
            v_ = cl::Buffer(view_.context, CL_MEM_READ_ONLY, 3 * capacity_ * sizeof(double));
            w_ = cl::Buffer(view_.context, CL_MEM_READ_ONLY, 3 * capacity_ * sizeof(double));
            weights_ = cl::Buffer(view_.context, CL_MEM_READ_WRITE, capacity_ * sizeof(double));
            sums_ = cl::Buffer(view_.context, CL_MEM_READ_WRITE, 7 * capacity_ * sizeof(double));
        }
        origin_ = frame.origin;
        dx_ = frame.dx;
        // the largest box: a grain's reach spans at most floor(2 reach / Δx) + 2 cells on each axis
        double largest = 0.0;
        for (const double radius : r) largest = std::max(largest, radius);
        const double reach = rule_ == CoverRule::psm ? largest + half_diagonal * dx_ : largest;
        const int span = static_cast<int>(std::floor(2.0 * reach / dx_)) + 2;
        box_cells_ = span * span * span;
        if (grains_ == 0) return;
        static_assert(sizeof(Vec3) == 3 * sizeof(double));
        view_.queue.enqueueWriteBuffer(x_, CL_FALSE, 0, 3 * grains_ * sizeof(double), x.data());
        view_.queue.enqueueWriteBuffer(r_, CL_FALSE, 0, grains_ * sizeof(double), r.data());
        if (rule_ == CoverRule::psm) run(claim_fraction_);
        run(claim_depth_);
        run(claim_grain_);
        view_.queue.flush();
    } catch (const cl::Error& e) {
        throw RunError(fmt::format("finding the grain cells on the OpenCL device failed: {} (error {})",
                                   e.what(), e.err()));
    }
}

void DeviceGrainCells::cover(std::span<const Vec3> v, std::span<const Vec3> w, double dt) {
    if (!view_.solids)
        throw std::logic_error("DeviceGrainCells::cover: the lattice was built without solids");
    if (grains_ == 0) return;
    try {
        view_.queue.enqueueWriteBuffer(v_, CL_FALSE, 0, 3 * grains_ * sizeof(double), v.data());
        view_.queue.enqueueWriteBuffer(w_, CL_FALSE, 0, 3 * grains_ * sizeof(double), w.data());
        cl_uint a = 7;
        for (const cl::Buffer* b : {&v_, &w_}) cover_.setArg(a++, *b);
        cover_.setArg(a++, dt);
        for (const cl::Buffer* b :
             {&fraction_, &owner_, &view_.type, &view_.tau, &view_.solid_fraction, &view_.solid_v, &weights_})
            cover_.setArg(a++, *b);
        cover_.setArg(a++, cl::Local(7 * group_ * sizeof(double)));
        if (view_.fill()) cover_.setArg(a++, view_.fill);
        run(cover_);
        view_.queue.flush();
        covered_ = true;
    } catch (const cl::Error& e) {
        throw RunError(fmt::format("covering the grain cells on the OpenCL device failed: {} (error {})",
                                   e.what(), e.err()));
    }
}

void DeviceGrainCells::request_sums() {
    sums_requested_ = true;
    sums_read_.resize(7 * grains_);
    grain_sums_.buoyancy_weight.resize(grains_);
    if (grains_ == 0) return;
    try {
        forces_.setArg(7, owner_);
        forces_.setArg(8, view_.solid_force);
        forces_.setArg(9, sums_);
        forces_.setArg(10, cl::Local(7 * group_ * sizeof(double)));
        run(forces_);
        view_.queue.enqueueReadBuffer(sums_, CL_FALSE, 0, sums_read_.size() * sizeof(double),
                                      sums_read_.data());
        view_.queue.enqueueReadBuffer(weights_, CL_FALSE, 0, grains_ * sizeof(double),
                                      grain_sums_.buoyancy_weight.data(), nullptr, &sums_ready_);
    } catch (const cl::Error& e) {
        throw RunError(fmt::format("summing the grains' forces on the OpenCL device failed: {} (error {})",
                                   e.what(), e.err()));
    }
}

const DeviceGrainCells::GrainSums& DeviceGrainCells::sums() {
    if (!sums_requested_) request_sums();
    sums_requested_ = false;
    GrainSums& out = grain_sums_;
    out.force.resize(grains_);
    out.torque.resize(grains_);
    out.cells.resize(grains_);
    if (grains_ == 0) return out;
    try {
        view_.queue.flush();
        sums_ready_.wait();  // (in order: the sums' read ended before the weights')
    } catch (const cl::Error& e) {
        throw RunError(fmt::format("reading the grains' forces from the OpenCL device failed: {} (error {})",
                                   e.what(), e.err()));
    }
    for (std::size_t g = 0; g < grains_; ++g) {
        out.force[g] = {sums_read_[7 * g], sums_read_[7 * g + 1], sums_read_[7 * g + 2]};
        out.torque[g] = {sums_read_[7 * g + 3], sums_read_[7 * g + 4], sums_read_[7 * g + 5]};
        out.cells[g] = sums_read_[7 * g + 6];
    }
    return out;
}

std::vector<CoveredCell> DeviceGrainCells::read_cells(const LatticeFrame& frame) const {
    std::vector<std::uint32_t> owner(cells_);
    std::vector<std::uint64_t> fraction(cells_);
    view_.queue.enqueueReadBuffer(owner_, CL_FALSE, 0, cells_ * sizeof(std::uint32_t), owner.data());
    view_.queue.enqueueReadBuffer(fraction_, CL_TRUE, 0, cells_ * sizeof(std::uint64_t), fraction.data());
    std::vector<CoveredCell> out;
    for (std::size_t k = 0; k < cells_; ++k) {
        if (owner[k] == no_grain) continue;
        const auto z = static_cast<int>(k / frame.plane), y = static_cast<int>(k % frame.plane / frame.row),
                   xi = static_cast<int>(k % frame.row);
        out.push_back({k, owner[k], frame.centre(xi, y, z),
                       rule_ == CoverRule::psm ? std::bit_cast<double>(fraction[k]) : 1.0});
    }
    return out;
}

}  // namespace sabo::coupling::opencl
