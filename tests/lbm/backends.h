// SPDX-License-Identifier: MIT
// The lattice tests run on both backends (docs/lbm.md, "Backends"): the CPU lattice, and the OpenCL one on
// the machine's first OpenCL device (POCL's CPU device where there is no GPU; the tests fail without one:
// scripts/install_deps.sh installs it).
#pragma once
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "lbm/fluid_lattice.h"
#include "lbm/opencl/opencl_lattice.h"

namespace sabo::lbm {

enum class Backend { cpu, opencl };

inline const opencl::DeviceInfo& test_device() {
    static const opencl::DeviceInfo device = opencl::choose_device("", "the tests' OpenCL device");
    return device;
}

// Steps a prepared host lattice on the chosen backend; after run() the host lattice holds the state.
template <class Real>
struct Stepper {
    FluidLattice<Real>& lattice;
    std::unique_ptr<opencl::OpenClLattice<Real>> device;
    Stepper(FluidLattice<Real>& l, Backend b) : lattice(l) {
        if (b == Backend::opencl) device = std::make_unique<opencl::OpenClLattice<Real>>(l, test_device());
    }
    void run(long steps) {
        if (!device) {
            for (long k = 0; k < steps; ++k) lattice.step();
            return;
        }
        device->step(static_cast<std::uint64_t>(steps));
        device->pull();
    }
};

inline std::string backend_name(const testing::TestParamInfo<Backend>& info) {
    return info.param == Backend::cpu ? "cpu" : "opencl";
}

#define SABO_ON_BOTH_BACKENDS(suite) \
    INSTANTIATE_TEST_SUITE_P(Backends, suite, testing::Values(Backend::cpu, Backend::opencl), backend_name)

}  // namespace sabo::lbm
