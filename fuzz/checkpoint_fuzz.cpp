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

#include "core/config.h"
#include "core/error.h"
#include "io/checkpoint.h"
#include "sim/case_setup.h"
#include "sim/channel_observer.h"
#include "sim/debris_observer.h"
#include "sim/debris_run.h"
#include "sim/frame_observers.h"
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
    Config cfg = Config::from_file(std::filesystem::path(SABO_SOURCE_DIR) / "cases" / file, overrides);
    (void)sim::case_type(cfg);  // read as `sabo run` reads it
    return cfg;
}

struct ChannelRun {
    Config cfg = tiny_case("slit_barrier.toml", {"release.solid_volume_m3=0.01", "case.end_time_s=1"});
    sim::PreparedCase pc = sim::prepare({"fuzz.toml", folder(), false}, cfg);
    sim::Simulation sim{dem::make_solver(pc.scene.particles, pc.scene.walls, pc.scene.gravity, pc.dem)};
    sim::ChannelObserver analysis{pc};
    sim::ParticleFrames frames{folder()};
    std::vector<sim::Observer*> observers{&analysis, &frames};
};

struct DebrisRun {
    explicit DebrisRun(bool grains)
        : cfg(tiny_case("debris_fluid.toml",
                        {"channel.width_m=0.4", "channel.length_m=2", "channel.height_m=0.6",
                         "debris.block_length_m=0.6", "debris.block_height_m=0.4", "lattice.dx_m=0.05",
                         "release.radius_mean_m=0.1", "barrier.face_x_m=1.2", "case.end_time_s=1",
                         grains ? "debris.solid_fraction=0.1" : "debris.solid_fraction=0"})),
          pc(sim::prepare_debris({"fuzz.toml", folder(), false}, cfg)),
          sim(sim::debris_simulation(pc, cells)),
          debris(pc, 1.0),
          fluid(folder(), pc.fluid.units) {
        observers = {&debris, &fluid};
        if (grains) observers.push_back(&grain_frames.emplace(folder()));
    }
    Config cfg;
    sim::PreparedDebris pc;
    std::vector<std::size_t> cells;
    sim::Simulation sim;
    sim::DebrisObserver debris;
    sim::FluidFrames fluid;
    std::optional<sim::ParticleFrames> grain_frames;
    std::vector<sim::Observer*> observers;
};

// Reads the checkpoint file into a fresh run of kind `mode`.
void read_into(int mode) {
    const auto load = [](auto& run) { sim::RunCheckpoint(folder(), run.cfg).load(run.sim, run.observers); };
    if (mode == 0) {
        ChannelRun run;
        load(run);
    } else {
        DebrisRun run(mode == 2);
        load(run);
    }
}

// A real checkpoint of each run, a few steps in, less its version and checksum, behind its mode byte.
void write_seeds(const std::filesystem::path& dir) {
    std::filesystem::create_directories(dir);
    const auto seed = [&](auto& run, int mode) {
        for (int k = 0; k < 20; ++k) run.sim.step();
        sim::RunCheckpoint(folder(), run.cfg).save(run.sim, run.observers, 0.0, 0.0, "");
        std::ifstream in(folder() / "checkpoint.bin", std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        std::ofstream out(dir / ("seed_" + std::to_string(mode)), std::ios::binary);
        out.put(static_cast<char>(mode));
        out.write(bytes.data() + sizeof io::checkpoint_magic,
                  static_cast<std::streamsize>(bytes.size() - sizeof io::checkpoint_magic - 8));
    };
    ChannelRun channel;
    seed(channel, 0);
    DebrisRun fluid(false);
    seed(fluid, 1);
    DebrisRun coupled(true);
    seed(coupled, 2);
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
