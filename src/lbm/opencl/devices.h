// SPDX-License-Identifier: MIT
// The OpenCL devices this machine offers (any platform: a GPU's driver, POCL's CPU device) and the choice of
// one for the lattice (`lattice.opencl_device`; docs/lbm.md, "Backends").
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace sabo::lbm::opencl {

struct DeviceInfo {
    int index = 0;  // in list_devices(): platforms in the ICD loader's order, devices in each platform's
    int platform_index = 0, device_index = 0;
    std::string platform, name, version;
    std::uint64_t global_memory = 0;   // bytes
    std::uint64_t max_allocation = 0;  // bytes in one buffer
    std::size_t max_work_group = 0;
    unsigned compute_units = 0;
    bool gpu = false;
    bool fp64 = false;  // cl_khr_fp64: float64 storage possible
    int sharers = 1;    // the ranks of a divided run that share it (each may take this share of its memory)
};

// Every device of every platform; empty when no OpenCL platform is installed (or the loader finds none).
[[nodiscard]] std::vector<DeviceInfo> list_devices();

// The device `spec` names: empty, the first GPU (else the first device); digits, its index in
// list_devices(); otherwise the first whose "platform: name" contains `spec` (any case). Throws InputError
// naming `key` and the devices there are.
[[nodiscard]] DeviceInfo choose_device(const std::string& spec, const std::string& key);

// The device of the ranks of a divided run on one machine (`local_size` of them): the `local_rank`-th after
// `chosen` (in turn, from it) among the devices with its platform and name, so that ranks on a machine with
// several GPUs of one kind take one each, and share them when there are more ranks (`sharers`: how many).
[[nodiscard]] DeviceInfo device_of_rank(const DeviceInfo& chosen, int local_rank, int local_size);
// The same among `devices` (list_devices()'s).
[[nodiscard]] DeviceInfo device_of_rank(const std::vector<DeviceInfo>& devices, const DeviceInfo& chosen,
                                        int local_rank, int local_size = 1);

// Bytes of device memory a lattice of `stored_cells` needs on the OpenCL backend (OpenClLattice): the
// populations, τ and the per-cell tables, the fields' snapshot and region, with `free_surface` the
// surface's per-cell state, and with `grains` the cells covered by grains (solid_cell_bytes); the wall
// links (13 bytes each) come on top once the geometry is known.
[[nodiscard]] std::uint64_t lattice_bytes(std::uint64_t stored_cells, bool single_precision,
                                          bool free_surface, bool grains = false);
// Per stored cell, the state of the cells grains cover: the lattice's share, velocity and force
// (OpenClLattice built with solids) and the grain cells' claims (coupling::opencl::DeviceGrainCells).
[[nodiscard]] std::uint64_t solid_cell_bytes(bool single_precision);

// Why a lattice needing `bytes` on `device`, `population_bytes` of them in one buffer, does not fit there
// ("the lattice needs … GiB on …, which has …"; a device shared by ranks: their share of it), or empty if
// it fits.
[[nodiscard]] std::string misfit(std::uint64_t bytes, std::uint64_t population_bytes,
                                 const DeviceInfo& device);

// The devices as `sabo devices` prints them, one per line (or why there are none).
[[nodiscard]] std::string describe_devices();

}  // namespace sabo::lbm::opencl
