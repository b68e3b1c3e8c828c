// SPDX-License-Identifier: MIT
#include "io/fluid_frames.h"

#include <fmt/format.h>

namespace sabo::io {

FluidFrameWriter::FluidFrameWriter(std::filesystem::path dir, const lbm::UnitConverter& units)
    : dir_(std::move(dir)), units_(units), pvd_(dir_ / "fluid.pvd") {
    std::filesystem::create_directories(dir_ / "frames");
}

template <class Real>
void FluidFrameWriter::write(const lbm::FluidLattice<Real>& l, double time) {
    const auto& sh = l.shape();
    const std::size_t n = sh.cells();
    std::vector<float> fill(n), type(n), pressure(n), viscosity(n), velocity(3 * n);
    const auto& u = units_;
    std::size_t c = 0;  // the image's cell: x fastest, then y, then z (no padding)
    for (int z = 0; z < sh.nz; ++z) {
        for (int y = 0; y < sh.ny; ++y) {
            for (int x = 0; x < sh.nx; ++x, ++c) {
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
    ImageDataWriter w(sh.nx, sh.ny, sh.nz, {}, u.dx());
    w.scalar("fill_fraction", std::move(fill));
    w.vector("velocity_m_s", std::move(velocity));
    w.scalar("pressure_Pa", std::move(pressure));
    w.scalar("cell_type", std::move(type));  // 0 fluid, 1 interface, 2 gas, 3 obstacle
    w.scalar("apparent_viscosity_Pa_s", std::move(viscosity));
    const std::string name = fmt::format("frames/fluid_{:05d}.vti", index_++);
    w.write(dir_ / name);
    pvd_.add(time, name);
}

template void FluidFrameWriter::write(const lbm::FluidLattice<float>&, double);
template void FluidFrameWriter::write(const lbm::FluidLattice<double>&, double);

}  // namespace sabo::io
