// SPDX-License-Identifier: MIT
// Choosing the OpenCL device (lattice.opencl_device) and what the backend refuses, with the key named.
#include <gtest/gtest.h>

#include <string>

#include "core/error.h"
#include "lbm/backends.h"
#include "lbm/opencl/devices.h"

namespace sabo::lbm {
namespace {

std::string message_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    return "(no error)";
}

TEST(OpenClDevices, TheTestMachineHasOneAndItCanBeNamed) {
    const auto devices = opencl::list_devices();
    ASSERT_FALSE(devices.empty()) << opencl::describe_devices();
    const auto& first = devices.front();
    EXPECT_EQ(opencl::choose_device("0", "k").name, first.name);
    EXPECT_EQ(opencl::choose_device(first.name.substr(0, 6), "k").name, first.name);
    EXPECT_NE(opencl::describe_devices().find(first.name), std::string::npos);
    const std::string missing =
        message_of([] { (void)opencl::choose_device("999", "lattice.opencl_device"); });
    EXPECT_NE(missing.find("lattice.opencl_device = \"999\": no such device"), std::string::npos) << missing;
    const std::string unnamed =
        message_of([] { (void)opencl::choose_device("no such gpu", "lattice.opencl_device"); });
    EXPECT_NE(unnamed.find("no device's name contains it"), std::string::npos) << unnamed;
}

TEST(OpenClDevices, ALatticeTooLargeForTheDeviceIsRefusedWithItsNumbers) {
    FluidLattice<float> l({64, 64, 64, {true, true, true}}, Rheology{});
    opencl::DeviceInfo small = test_device();
    small.global_memory = 1 << 20;
    const std::string m = message_of([&] { opencl::OpenClLattice<float>::check_fits(l, small); });
    // 64³ cells of 19 + 1 floats, 11 bytes of tables and 38 of the snapshot and region: 0.03 GiB
    EXPECT_NE(m.find("the lattice needs 0.03 GiB on the OpenCL device"), std::string::npos) << m;
    EXPECT_NE(m.find("which has 0.00 GiB"), std::string::npos) << m;
    EXPECT_GT(opencl::OpenClLattice<float>::device_bytes(l), 64u * 64 * 64 * 19 * 4);
}

TEST(OpenClDevices, WhatTheBackendDoesNotCarryYetIsRefused) {
    FluidLattice<double> l({8, 8, 8}, Rheology{});
    for (int z = 0; z < 4; ++z)
        for (int y = 0; y < 8; ++y)
            for (int x = 0; x < 8; ++x) l.set_fluid(x, y, z, 1.0, {});
    l.prepare();
    const SolidCell grain{l.index(4, 4, 1), {}, 1.0};
    l.set_solid_cells(std::span<const SolidCell>(&grain, 1));
    const std::string m = message_of([&] { opencl::OpenClLattice<double> d(l, test_device()); });
    EXPECT_NE(m.find("lattice.device = \"opencl\": grain cells (the coupling) are not carried"),
              std::string::npos)
        << m;
}

// The ranks of a divided run on one machine take the devices of the chosen one's kind in turn, from it;
// other kinds are never taken, and one device of its kind serves every rank.
TEST(OpenClDevices, RanksOnOneMachineTakeTheDevicesOfTheChosenKindInTurn) {
    std::vector<opencl::DeviceInfo> devices;
    for (int i = 0; i < 5; ++i) {
        opencl::DeviceInfo d;
        d.index = i;
        d.platform = i == 0 ? "Portable Computing Language" : "NVIDIA CUDA";
        d.name = i == 0 ? "cpu" : (i == 3 ? "Other GPU" : "H100");
        devices.push_back(d);
    }
    const auto index_of = [&](int chosen, int local_rank) {
        return opencl::device_of_rank(devices, devices[static_cast<std::size_t>(chosen)], local_rank).index;
    };
    EXPECT_EQ(index_of(1, 0), 1);
    EXPECT_EQ(index_of(1, 1), 2);
    EXPECT_EQ(index_of(1, 2), 4);  // (device 3 is of another kind)
    EXPECT_EQ(index_of(1, 3), 1);  // more ranks than devices: they share
    EXPECT_EQ(index_of(2, 1), 4);  // from the chosen one on
    EXPECT_EQ(index_of(3, 5), 3);
    EXPECT_EQ(index_of(0, 1), 0);
    // 5 ranks on the 3 devices of one kind: ranks 0 and 3 share device 1, 1 and 4 device 2, rank 2 has 4
    const auto sharers = [&](int local_rank) {
        return opencl::device_of_rank(devices, devices[1], local_rank, 5).sharers;
    };
    EXPECT_EQ(sharers(0), 2);
    EXPECT_EQ(sharers(1), 2);
    EXPECT_EQ(sharers(2), 1);
    EXPECT_EQ(sharers(3), 2);
    // a shared device offers each rank its share of the memory, and the refusal says so
    opencl::DeviceInfo shared = devices[1];
    shared.global_memory = 4ULL << 30;
    shared.max_allocation = 1ULL << 30;
    EXPECT_EQ(opencl::misfit(3ULL << 30, 1ULL << 29, shared), "");
    shared.sharers = 2;
    const std::string why = opencl::misfit(3ULL << 30, 1ULL << 29, shared);
    EXPECT_NE(why.find("which has 2.00 GiB for each of the 2 ranks that share it"), std::string::npos) << why;
}

}  // namespace
}  // namespace sabo::lbm
