// SPDX-License-Identifier: MIT
#include "lbm/opencl/devices.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>

#include "core/error.h"
#include "lbm/opencl/cl.h"

namespace sabo::lbm::opencl {

namespace {

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
    return s;
}

std::string trimmed(std::string s) {
    while (!s.empty() && (s.back() == '\0' || std::isspace(static_cast<unsigned char>(s.back()))))
        s.pop_back();
    return s;
}

}  // namespace

std::vector<DeviceInfo> list_devices() {
    std::vector<DeviceInfo> out;
    std::vector<cl::Platform> platforms;
    try {
        cl::Platform::get(&platforms);
    } catch (const cl::Error&) {
        return out;  // no ICD installed: CL_PLATFORM_NOT_FOUND_KHR
    }
    for (std::size_t p = 0; p < platforms.size(); ++p) {
        std::vector<cl::Device> devices;
        try {
            platforms[p].getDevices(CL_DEVICE_TYPE_ALL, &devices);
        } catch (const cl::Error&) {
            continue;  // a platform without devices
        }
        for (std::size_t d = 0; d < devices.size(); ++d) {
            const cl::Device& dev = devices[d];
            DeviceInfo info;
            info.index = static_cast<int>(out.size());
            info.platform_index = static_cast<int>(p);
            info.device_index = static_cast<int>(d);
            info.platform = trimmed(platforms[p].getInfo<CL_PLATFORM_NAME>());
            info.name = trimmed(dev.getInfo<CL_DEVICE_NAME>());
            info.version = trimmed(dev.getInfo<CL_DEVICE_VERSION>());
            info.global_memory = dev.getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>();
            info.max_allocation = dev.getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>();
            info.max_work_group = dev.getInfo<CL_DEVICE_MAX_WORK_GROUP_SIZE>();
            info.compute_units = dev.getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>();
            info.gpu = (dev.getInfo<CL_DEVICE_TYPE>() & CL_DEVICE_TYPE_GPU) != 0;
            info.fp64 = dev.getInfo<CL_DEVICE_EXTENSIONS>().find("cl_khr_fp64") != std::string::npos;
            out.push_back(std::move(info));
        }
    }
    return out;
}

std::uint64_t solid_cell_bytes(bool single_precision) {
    const std::uint64_t real = single_precision ? 4 : 8;
    // ε and v (4 reals), the force (3 sums); the claims' share and depth (8 bytes each) and owner (4)
    return 4 * real + 3 * 8 + 8 + 8 + 4;
}

std::uint64_t lattice_bytes(std::uint64_t stored_cells, bool single_precision, bool free_surface,
                            bool grains) {
    const std::uint64_t real = single_precision ? 4 : 8, q = 19;
    // populations (and their slot padding, < 1 %), τ, type, links, element, link index
    std::uint64_t per_cell = q * real + real + 1 + 4 + 2 + 4;
    // λ twice, m, ρ, u, n, the outgoing populations, flags, excess, shares, orphan, the region's excess, the
    // pocket search's marks
    if (free_surface) per_cell += (q + 8) * real + 6 * 8 + 5;
    // the snapshot of the fields (type, λ, τ, u; ρ and m as sums) and the region of the summaries
    per_cell += 1 + 5 * real + 2 * 8 + 1;
    if (grains) per_cell += solid_cell_bytes(single_precision) + 1;  // (+ the snapshot's covered flag)
    return stored_cells * per_cell + stored_cells / 64 * q * real;
}

std::string misfit(std::uint64_t bytes, std::uint64_t population_bytes, const DeviceInfo& device) {
    const auto sharers = static_cast<std::uint64_t>(std::max(device.sharers, 1));
    const std::uint64_t share = device.global_memory / sharers;
    if (bytes <= share && population_bytes <= device.max_allocation) return {};
    constexpr double gib = 1024.0 * 1024.0 * 1024.0;
    return fmt::format(
        "the lattice needs {:.2f} GiB on the OpenCL device {} ({:.2f} GiB of populations in one buffer), "
        "which has {:.2f} GiB{} ({:.2f} GiB in one buffer)",
        static_cast<double>(bytes) / gib, device.name, static_cast<double>(population_bytes) / gib,
        static_cast<double>(share) / gib,
        sharers > 1 ? fmt::format(" for each of the {} ranks that share it", sharers) : std::string(),
        static_cast<double>(device.max_allocation) / gib);
}

std::string describe_devices() {
    const auto devices = list_devices();
    if (devices.empty())
        return "no OpenCL device found (no platform installed: a GPU's OpenCL driver, or Debian's "
               "pocl-opencl-icd for the CPU)\n";
    std::string s;
    for (const DeviceInfo& d : devices)
        s += fmt::format(
            "{}: {}: {} ({}, {}), {:.1f} GiB, largest buffer {:.1f} GiB, {} compute units, "
            "float64 {}\n",
            d.index, d.platform, d.name, d.gpu ? "GPU" : "not a GPU", d.version,
            static_cast<double>(d.global_memory) / (1024.0 * 1024.0 * 1024.0),
            static_cast<double>(d.max_allocation) / (1024.0 * 1024.0 * 1024.0), d.compute_units,
            d.fp64 ? "yes" : "no");
    return s;
}

DeviceInfo choose_device(const std::string& spec, const std::string& key) {
    const auto devices = list_devices();
    if (devices.empty())
        throw InputError(
            fmt::format("{}: no OpenCL device on this machine (install a GPU's OpenCL driver, or "
                        "pocl-opencl-icd for the CPU; `sabo devices` lists what there is)",
                        key));
    if (spec.empty()) {
        const auto gpu =
            std::find_if(devices.begin(), devices.end(), [](const DeviceInfo& d) { return d.gpu; });
        return gpu != devices.end() ? *gpu : devices.front();
    }
    if (std::all_of(spec.begin(), spec.end(), [](unsigned char c) { return std::isdigit(c) != 0; })) {
        const auto i = spec.size() < 6 ? std::stoul(spec) : devices.size();
        if (i < devices.size()) return devices[i];
        throw InputError(fmt::format("{} = \"{}\": no such device (0 to {}):\n{}", key, spec,
                                     devices.size() - 1, describe_devices()));
    }
    for (const DeviceInfo& d : devices)
        if (lower(d.platform + ": " + d.name).find(lower(spec)) != std::string::npos) return d;
    throw InputError(fmt::format("{} = \"{}\": no device's name contains it; there are:\n{}", key, spec,
                                 describe_devices()));
}

DeviceInfo device_of_rank(const DeviceInfo& chosen, int local_rank, int local_size) {
    return device_of_rank(list_devices(), chosen, local_rank, local_size);
}

DeviceInfo device_of_rank(const std::vector<DeviceInfo>& devices, const DeviceInfo& chosen, int local_rank,
                          int local_size) {
    std::vector<DeviceInfo> alike;
    std::size_t first = 0;
    for (const DeviceInfo& d : devices) {
        if (d.platform != chosen.platform || d.name != chosen.name) continue;
        if (d.index == chosen.index) first = alike.size();
        alike.push_back(d);
    }
    if (alike.empty()) return chosen;
    const auto rank = static_cast<std::size_t>(std::max(local_rank, 0)), count = alike.size();
    DeviceInfo out = alike[(first + rank) % count];
    // the local ranks that land on the same device: rank, rank ± count, …
    const auto ranks = static_cast<std::size_t>(std::max(local_size, 1));
    out.sharers = 0;
    for (std::size_t q = rank % count; q < ranks; q += count) ++out.sharers;
    out.sharers = std::max(out.sharers, 1);
    return out;
}

}  // namespace sabo::lbm::opencl
