// SPDX-License-Identifier: MIT
#include "io/fluid_frames.h"

#include <fmt/format.h>

namespace sabo::io {

FluidFrameWriter::FluidFrameWriter(std::filesystem::path dir, const lbm::UnitConverter& units)
    : dir_(std::move(dir)), units_(units), pvd_(dir_ / "fluid.pvd") {
    std::filesystem::create_directories(dir_ / "frames");
}

void FluidFrameWriter::write(const lbm::FluidFields& l, double time, const FluidPieces& pieces) {
    const int nx = l.nx;
    const std::size_t n = l.cells();
    std::vector<float> fill(n), type(n), pressure(n), viscosity(n), velocity(3 * n);
    for (std::size_t c = 0; c < n; ++c) {  // the image's cells: x fastest, then y, then z (no padding)
        fill[c] = static_cast<float>(l.fill[c]);
        type[c] = static_cast<float>(static_cast<int>(l.type[c]));
        if (!l.wet(c)) continue;
        const double rho = l.density[c];
        const Vec3& v = l.velocity[c];
        pressure[c] = static_cast<float>(units_.stress_si((rho - 1.0) / 3.0));  // p − p_atm = c_s² (ρ − ρ_A)
        viscosity[c] = static_cast<float>(units_.density() * (l.tau[c] - 0.5) / 3.0 * units_.dx() *
                                          units_.dx() / units_.dt());
        velocity[3 * c] = static_cast<float>(units_.velocity_si(v.x));
        velocity[3 * c + 1] = static_cast<float>(units_.velocity_si(v.y));
        velocity[3 * c + 2] = static_cast<float>(units_.velocity_si(v.z));
    }
    ImageDataWriter w(nx, l.ny, l.nz, {}, units_.dx());
    w.scalar("fill_fraction", std::move(fill));
    w.vector("velocity_m_s", std::move(velocity));
    w.scalar("pressure_Pa", std::move(pressure));
    w.scalar("cell_type", std::move(type));  // 0 fluid, 1 interface, 2 gas, 3 obstacle
    w.scalar("apparent_viscosity_Pa_s", std::move(viscosity));
    const std::string name = fmt::format("frames/fluid_{:05d}", index_++);
    if (pieces.cuts.size() < 3) {
        w.write(dir_ / (name + ".vti"));
        pvd_.add(time, name + ".vti");
        return;
    }
    const std::string stem = std::filesystem::path(name).filename().string();
    w.set_piece(pieces.cuts[static_cast<std::size_t>(pieces.rank)], pieces.cuts.back());
    w.write(dir_ / fmt::format("{}_r{}.vti", name, pieces.rank));
    if (pieces.rank != 0) return;
    std::vector<ImageDataWriter::Piece> all;
    for (std::size_t r = 0; r + 1 < pieces.cuts.size(); ++r)
        all.push_back({fmt::format("{}_r{}.vti", stem, r), pieces.cuts[r], pieces.cuts[r + 1]});
    w.write_parallel(dir_ / (name + ".pvti"), all);
    pvd_.add(time, name + ".pvti");
}

}  // namespace sabo::io
