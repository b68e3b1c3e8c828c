// SPDX-License-Identifier: MIT
// libFuzzer target: the checkpoint reader (scripts/fuzz.sh). Each input is the content of a checkpoint,
// what follows its layout version: the harness writes the version before it and the checksum after it, so
// that the fuzzer reaches every check of the content (a file whose checksum does not match is refused
// before any of it is read: tests/scripts/check_bad_checkpoint.py). The first byte picks the run it is
// read into, as `sabo resume` would: 0 a DEM channel run, 1 the fluid alone, 2 grains and fluid coupled
// (tiny cases). A bad file must end in InputError; another exception escaping, a crash, a sanitizer
// report, a hang or memory beyond the limit is a finding. With SABO_FUZZ_WRITE_SEEDS=DIR it first writes a
// real checkpoint of each run, a few steps in, into DIR as seeds.
#include <spdlog/spdlog.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include "cases/registry.h"
#include "core/config.h"
#include "core/error.h"
#include "io/checkpoint.h"
#include "sim/run_checkpoint.h"

namespace {

using namespace sabo;

const std::filesystem::path& folder() {
    static const std::filesystem::path dir = [] {
        auto d =
            std::filesystem::temp_directory_path() / ("sabo_fuzz_checkpoint_" + std::to_string(::getpid()));
        std::filesystem::create_directories(d);
        return d;
    }();
    return dir;
}

Config tiny_case(const char* file, std::vector<std::string> overrides) {
    overrides.push_back("output.report=false");
    return Config::from_file(std::filesystem::path(SABO_SOURCE_DIR) / "cases" / file, overrides);
}

// A tiny case built as `sabo run` builds it (its case type's simulation and observers), not run.
struct CaseRun {
    CaseRun(const char* file, std::vector<std::string> overrides)
        : cfg(tiny_case(file, std::move(overrides))), type(cases::make_case_type(cfg)) {
        type->prepare({"fuzz.toml", folder(), false}, cfg);
        sim.emplace(std::move(*type->build(type->domain(nullptr), control, false)));
        observers = type->observers(*sim);
    }
    Config cfg;
    std::unique_ptr<sim::CaseType> type;
    sim::RunControl control{1.0, 0};
    std::optional<sim::Simulation> sim;
    std::vector<sim::Observer*> observers;
};

CaseRun channel_run() {
    return {"slit_barrier.toml", {"release.solid_volume_m3=0.01", "case.end_time_s=1"}};
}

CaseRun debris_run(bool grains) {
    return {"debris_fluid.toml",
            {"channel.width_m=0.4", "channel.length_m=2", "channel.height_m=0.6", "debris.block_length_m=0.6",
             "debris.block_height_m=0.4", "lattice.dx_m=0.05", "release.radius_mean_m=0.1",
             "barrier.face_x_m=1.2", "case.end_time_s=1",
             grains ? "debris.solid_fraction=0.1" : "debris.solid_fraction=0"}};
}

// Reads the checkpoint file into a fresh run of kind `mode`.
void read_into(int mode) {
    CaseRun run = mode == 0 ? channel_run() : debris_run(mode == 2);
    sim::RunCheckpoint(folder(), run.cfg).load(*run.sim, run.observers);
}

// A real checkpoint of each run, a few steps in, less its version and checksum, behind its mode byte.
void write_seeds(const std::filesystem::path& dir) {
    std::filesystem::create_directories(dir);
    const auto seed = [&](CaseRun run, int mode) {
        for (int k = 0; k < 20; ++k) run.sim->step();
        sim::RunCheckpoint(folder(), run.cfg).save(*run.sim, run.observers, 0.0, 0.0, "");
        std::ifstream in(folder() / "checkpoint.bin", std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        std::ofstream out(dir / ("seed_" + std::to_string(mode)), std::ios::binary);
        out.put(static_cast<char>(mode));
        out.write(bytes.data() + sizeof io::checkpoint_magic,
                  static_cast<std::streamsize>(bytes.size() - sizeof io::checkpoint_magic - 8));
    };
    seed(channel_run(), 0);
    seed(debris_run(false), 1);
    seed(debris_run(true), 2);
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    spdlog::set_level(spdlog::level::off);
    if (const char* dir = std::getenv("SABO_FUZZ_WRITE_SEEDS")) write_seeds(dir);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    io::Checksum sum;
    sum.add(io::checkpoint_magic, sizeof io::checkpoint_magic);
    sum.add(data + 1, size - 1);
    const std::uint64_t checksum = sum.value();
    {
        std::ofstream out(folder() / "checkpoint.bin", std::ios::binary | std::ios::trunc);
        out.write(io::checkpoint_magic, sizeof io::checkpoint_magic);
        out.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
        out.write(reinterpret_cast<const char*>(&checksum), sizeof checksum);
    }
    try {
        read_into(data[0] % 3);
    } catch (const InputError&) {
        // refused, as it should be
    }
    return 0;
}
