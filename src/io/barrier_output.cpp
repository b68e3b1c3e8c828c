// SPDX-License-Identifier: MIT
#include "io/barrier_output.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <string>
#include <tuple>
#include <vector>

#include "io/atomic_file.h"
#include "io/vtk_writer.h"

namespace sabo::io {

void write_force_maps(const std::filesystem::path& dir, const scenario::BarrierInfo& barrier,
                      const analysis::BarrierForceMonitor& forces) {
    const auto& el = barrier.elements;
    const std::size_t n = el.size();
    std::vector<Vec3> centres(n);
    std::vector<double> pile(n), magnitude(n);
    for (std::size_t e = 0; e < n; ++e) {
        centres[e] = el[e].centre;
        pile[e] = el[e].pile;
    }
    const std::array<std::pair<const char*, const analysis::ForceMap*>, 4> maps = {
        {{"t1", &forces.map_t1()},
         {"t2", &forces.map_t2()},
         {"t3", &forces.map_t3()},
         {"end", &forces.map_end()}}};
    const std::vector<Vec3> zero(n);
    for (const auto& [name, map] : maps) {
        const std::vector<Vec3>& f = map->force.size() == n ? map->force : zero;  // never taken: zeros
        for (std::size_t e = 0; e < n; ++e) magnitude[e] = norm(f[e]);
        PolyDataWriter w(centres);
        w.vector("force_N", f);
        w.scalar("force_magnitude_N", magnitude);
        w.scalar("pile", pile);
        w.write(dir / fmt::format("barrier_map_{}.vtp", name));
    }
    PolyDataWriter env(centres);
    env.scalar("max_force_magnitude_N", forces.envelope());
    env.scalar("max_fluid_force_magnitude_N", forces.fluid_envelope());
    env.scalar("pile", pile);
    env.write(dir / "barrier_envelope.vtp");

    std::string csv = "element,pile,x_m,y_m,z_m,height_m";
    for (const auto& [name, map] : maps)
        csv += fmt::format(",{0}_fx_N,{0}_fy_N,{0}_fz_N,{0}_magnitude_N", name);
    csv += ",envelope_N,envelope_fluid_N\n";
    for (std::size_t e = 0; e < n; ++e) {
        csv += fmt::format("{},{},{:.6g},{:.6g},{:.6g},{:.6g}", e, el[e].pile, el[e].centre.x, el[e].centre.y,
                           el[e].centre.z, el[e].height);
        for (const auto& [name, map] : maps) {
            const Vec3 f = map->force.size() == n ? map->force[e] : Vec3{};
            csv += fmt::format(",{:.9g},{:.9g},{:.9g},{:.9g}", f.x, f.y, f.z, norm(f));
        }
        csv += fmt::format(",{:.9g},{:.9g}\n", forces.envelope()[e], forces.fluid_envelope()[e]);
    }
    csv += fmt::format("# map times (s): t1 {:.9g} t2 {:.9g} t3 {:.9g} end {:.9g}\n", forces.map_t1().time,
                       forces.map_t2().time, forces.map_t3().time, forces.map_end().time);
    write_text_atomically(dir / "barrier_maps.csv", csv);
}

void write_facet_maps(const std::filesystem::path& dir, const geometry::TriangleMesh& mesh,
                      const analysis::FacetMaps& maps, bool grains, bool fluid) {
    const std::size_t n = mesh.triangles.size();
    std::vector<std::int64_t> connectivity, offsets;
    std::vector<double> part(n), area(n);
    std::vector<Vec3> outward(n);
    for (std::size_t t = 0; t < n; ++t) {
        for (const std::uint32_t v : mesh.triangles[t]) connectivity.push_back(v);
        offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
        part[t] = mesh.part[t];
        const Vec3 a = mesh.area_vector(t);  // twice the area, outward
        area[t] = 0.5 * norm(a);
        outward[t] = a / norm(a);
    }
    SurfaceWriter w(mesh.vertices, connectivity, offsets);
    w.cell_scalar("part", part);
    w.cell_scalar("area_m2", area);
    static constexpr std::array<const char*, analysis::FacetMaps::count> names{
        "t1", "t2", "t3", "end", "grains_peak", "fluid_peak"};
    // (the writer holds views of the arrays until it writes: they stay in place as the deques grow)
    std::deque<std::vector<Vec3>> forces;
    std::deque<std::vector<double>> pressures;
    for (std::size_t k = 0; k < names.size(); ++k) {
        if ((k == analysis::FacetMaps::grains_peak && !grains) ||
            (k == analysis::FacetMaps::fluid_peak && !fluid))
            continue;
        std::vector<double> total(n, 0.0);
        for (const auto& [on, component, force] :
             {std::tuple{grains, "grain", &maps.grains[k]}, std::tuple{fluid, "fluid", &maps.fluid[k]}}) {
            if (!on) continue;
            // (zeros for a map never taken)
            const std::vector<Vec3>& f =
                forces.emplace_back(force->size() == n ? *force : std::vector<Vec3>(n));
            std::vector<double>& pressure = pressures.emplace_back(n);
            for (std::size_t t = 0; t < n; ++t) {
                pressure[t] = -dot(f[t], outward[t]) / area[t];
                total[t] += pressure[t];
            }
            w.cell_vector(fmt::format("{}_force_{}_N", component, names[k]), f);
            w.cell_scalar(fmt::format("{}_pressure_{}_Pa", component, names[k]), pressure);
        }
        if (grains && fluid)
            w.cell_scalar(fmt::format("pressure_{}_Pa", names[k]), pressures.emplace_back(std::move(total)));
    }
    w.write(dir / "barrier_facets.vtp");
}

void write_arching(const std::filesystem::path& dir, const analysis::ArchingMonitor& arching, double t0) {
    std::string csv =
        "outlet,y_lo_m,y_hi_m,interval,z_lo_m,z_hi_m,grains,kinetic_energy_J,halted,t_stop_s,t_stop_minus_t0_"
        "s\n";
    for (std::size_t o = 0; o < arching.outlets().size(); ++o) {
        const auto& out = arching.outlets()[o];
        for (std::size_t k = 0; k < out.intervals.size(); ++k) {
            const auto& iv = out.intervals[k];
            const bool h = iv.halted();
            csv += fmt::format("{},{:.6g},{:.6g},{},{:.6g},{:.6g},{},{:.6g},{},{},{}\n", o, out.outlet.lo,
                               out.outlet.hi, k, iv.z_lo, iv.z_hi, iv.grains, iv.kinetic_energy, h ? 1 : 0,
                               h ? fmt::format("{:.6g}", iv.below_since) : "",
                               h && std::isfinite(t0) ? fmt::format("{:.6g}", iv.below_since - t0) : "");
        }
    }
    write_text_atomically(dir / "arching.csv", csv);
}

// Volume fraction of large grains in slabs of the deposit (reference case C4): slabs 25 cm long in X going
// upstream from the barrier face, three height bands over H_bar; retained grains only.
void write_deposit_composition(const std::filesystem::path& dir, const scenario::ChannelCase& scene,
                               const dem::Particles& p) {
    const auto& b = scene.barrier;
    const double split = 0.5 * (scene.release.r_large + scene.release.r_small), slab = 0.25;
    const double band = scene.height / 3.0;
    const int n_slabs = static_cast<int>(std::ceil(b.face_x / slab));
    std::vector<double> large(static_cast<std::size_t>(n_slabs) * 3, 0.0), total(large.size(), 0.0);
    for (std::size_t i = 0; i < p.n_mobile; ++i) {
        const double d = b.upstream_distance(p.x[i]);
        if (d < 0.0) continue;
        const int k = std::min(n_slabs - 1, static_cast<int>(d / slab));
        const int z = std::clamp(static_cast<int>(p.x[i].z / band), 0, 2);
        const double v = dem::sphere_volume(p.r[i]);
        const auto cell = static_cast<std::size_t>(k) * 3 + static_cast<std::size_t>(z);
        total[cell] += v;
        if (p.r[i] > split) large[cell] += v;
    }
    std::string csv =
        "upstream_from_m,upstream_to_m,z_lo_m,z_hi_m,volume_large_m3,volume_total_m3,large_fraction\n";
    for (int k = 0; k < n_slabs; ++k) {
        for (int z = 0; z < 3; ++z) {
            const auto cell = static_cast<std::size_t>(k) * 3 + static_cast<std::size_t>(z);
            if (total[cell] <= 0.0) continue;
            csv += fmt::format("{:.3f},{:.3f},{:.3f},{:.3f},{:.6g},{:.6g},{:.6g}\n", k * slab, (k + 1) * slab,
                               z * band, (z + 1) * band, large[cell], total[cell], large[cell] / total[cell]);
        }
    }
    write_text_atomically(dir / "deposit_composition.csv", csv);
}

void add_barrier_face(JsonObject& js, const scenario::BarrierInfo& barrier) {
    const Vec3& n = barrier.face_normal;
    const std::array<double, 3> normal{n.x, n.y, n.z};
    js.number("barrier_face_x_m", barrier.face_x).numbers("barrier_face_normal", normal);
}

}  // namespace sabo::io
