// SPDX-License-Identifier: MIT
#include "io/fluid_frames.h"

#include <fmt/format.h>

namespace sabo::io {

FluidFrameWriter::FluidFrameWriter(std::filesystem::path dir, const lbm::UnitConverter& units)
    : dir_(std::move(dir)), units_(units), pvd_(dir_ / "fluid.pvd") {
    std::filesystem::create_directories(dir_ / "frames");
}

template <class Real>
void FluidFrameWriter::write(const lbm::FluidLattice<Real>& l, double time, const FluidPieces& pieces) {
    const auto& sh = l.shape();
    const int x0 = l.own_begin(), nx = l.own_end() - l.own_begin();  // the own planes
    const std::size_t n =
        static_cast<std::size_t>(nx) * static_cast<std::size_t>(sh.ny) * static_cast<std::size_t>(sh.nz);
    std::vector<float> fill(n), type(n), pressure(n), viscosity(n), velocity(3 * n);
    const auto& u = units_;
    std::size_t c = 0;  // the image's cell: x fastest, then y, then z (no padding)
    for (int z = 0; z < sh.nz; ++z) {
        for (int y = 0; y < sh.ny; ++y) {
            for (int x = x0; x < x0 + nx; ++x, ++c) {
                const std::size_t k = l.index(x, y, z);
                fill[c] = static_cast<float>(l.fill(k));
                type[c] = static_cast<float>(static_cast<int>(l.type(k)));
                if (l.type(k) != lbm::CellType::fluid && l.type(k) != lbm::CellType::interface) continue;
                double rho = 0.0;
                Vec3 v;
                l.moments(k, rho, v);
                pressure[c] =
                    static_cast<float>(u.stress_si((rho - 1.0) / 3.0));  // p − p_atm = c_s² (ρ − ρ_A)
                viscosity[c] =
                    static_cast<float>(u.density() * (l.tau(k) - 0.5) / 3.0 * u.dx() * u.dx() / u.dt());
                velocity[3 * c] = static_cast<float>(u.velocity_si(v.x));
                velocity[3 * c + 1] = static_cast<float>(u.velocity_si(v.y));
                velocity[3 * c + 2] = static_cast<float>(u.velocity_si(v.z));
            }
        }
    }
    ImageDataWriter w(nx, sh.ny, sh.nz, {}, u.dx());
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

template void FluidFrameWriter::write(const lbm::FluidLattice<float>&, double, const FluidPieces&);
template void FluidFrameWriter::write(const lbm::FluidLattice<double>&, double, const FluidPieces&);

}  // namespace sabo::io
