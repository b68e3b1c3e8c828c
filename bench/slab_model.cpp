// SPDX-License-Identifier: MIT
// The slab-decomposition model of docs/scaling.md: how a coupled run's work divides among N ranks along
// the channel, with equal slabs and with slabs balanced on the measured work (parallel::SlabPartition), and
// the time its slab boundaries cost on a cluster network.
//
//   slab_model PLANES.csv NY NZ [REFINE [THREADS]]
//
// PLANES.csv: bench/plane_costs.py of a debris run (per frame and lattice plane along X: fluid, interface,
// gas and obstacle cells, grain centres); NY, NZ: the lattice's cells across and up; REFINE: the same flow
// on a lattice REFINE times finer (each plane becomes REFINE planes of REFINE² times the cells; interface
// cells, a surface, grow REFINE-fold per plane); THREADS: OpenMP threads per rank (each at the measured
// 2-thread efficiency). Prints one row per rank count, averaged over the frames after the release (frame 0
// is the block at rest); the last column overlaps the boundary traffic with the slab's interior work.
#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "parallel/slab_partition.h"

namespace {

// Work per lattice step in interior-fluid-cell units, from the full-size C5 Bingham run (float64, 2
// threads, bench/RESULTS.md "Free-surface passes"): an interior cell ~14 ns of thread time, an interface
// cell ~1 µs (70 interior cells), a gas cell ~1 ns (the run's first steps: 700,000 wet and 2.9 M gas cells
// at 62 steps/s), a grain ~270 ns (two DEM sub-steps at 1.5e7 particle-steps/s on two threads).
constexpr double interior_seconds = 14e-9;
constexpr double w_fluid = 1.0, w_interface = 70.0, w_gas = 0.07, w_grain = 19.0;
// What crosses a slab boundary per lattice step, per boundary cell and direction: the 5 populations
// whose c_x points across (float64) and, for the free surface, the ghost plane's fill fraction, mass and
// cell type; three messages a step per neighbour (populations, surface fields, conversions). Grains near
// the boundary: position, velocity, spin and radius out, force and torque back, at each of 2 sub-steps.
constexpr double halo_bytes_per_cell = 5 * 8 + 8 + 8 + 1;
constexpr double messages_per_neighbour = 3;
constexpr double ghost_grain_bytes = 2 * (10 * 8 + 6 * 8);
// A cluster network: 2 µs a message, 10 GB/s a link (effective, both ways at once).
constexpr double latency_s = 2e-6, bandwidth_B_s = 10e9;
// OpenMP threads inside a rank: the lattice's 2-thread speed-up 1.70 (dam break, bench/RESULTS.md).
constexpr double thread_efficiency = 0.85;

struct Plane {
    double fluid = 0, interface = 0, gas = 0, grains = 0;
};

}  // namespace

int main(int argc, char** argv) {
    if (argc < 4) {
        std::fprintf(stderr, "usage: slab_model PLANES.csv NY NZ [REFINE]\n");
        return 2;
    }
    const int ny = std::stoi(argv[2]), nz = std::stoi(argv[3]);
    const int refine = argc > 4 ? std::stoi(argv[4]) : 1;
    const int threads = argc > 5 ? std::stoi(argv[5]) : 1;
    const double rank_speed = threads == 1 ? 1.0 : threads * thread_efficiency;
    std::ifstream in(argv[1]);
    std::string line;
    std::getline(in, line);
    std::map<int, std::vector<Plane>> frames;
    while (std::getline(in, line)) {
        std::stringstream ss(line);
        std::string f[8];
        for (auto& v : f) std::getline(ss, v, ',');
        const int frame = std::stoi(f[0]);
        if (frame == 0) continue;
        const double r = refine;
        const Plane p{std::stod(f[3]) * r * r, std::stod(f[4]) * r,
                      (std::stod(f[5]) + std::stod(f[6])) * r * r, std::stod(f[7]) / r};
        for (int k = 0; k < refine; ++k) frames[frame].push_back(p);
    }
    const double boundary_cells = static_cast<double>(ny) * nz * refine * refine;
    const int planes = static_cast<int>(frames.begin()->second.size());
    fmt::print("{} frames, {} planes of {} x {} cells ({:.3g} cells)\n", frames.size(), planes, ny * refine,
               nz * refine, boundary_cells * planes);
    fmt::print("{} thread(s) per rank\n", threads);
    fmt::print("{:>6} {:>10} {:>10} {:>12} {:>12} {:>12} {:>10} {:>10} {:>12}\n", "ranks", "imb_equal",
               "imb_bal", "comp_ms", "halo_MB", "comm_ms", "eff_equal", "eff_bal", "eff_overlap");
    for (int ranks = 2; ranks <= planes / 2; ranks *= 2) {
        double imb_eq = 0, imb_bal = 0, comp = 0, comm = 0, eff_eq = 0, eff_bal = 0, eff_overlap = 0,
               halo = 0;
        for (const auto& [frame, plane] : frames) {
            std::vector<double> cost(plane.size());
            double total = 0;
            for (std::size_t x = 0; x < plane.size(); ++x) {
                cost[x] = w_fluid * plane[x].fluid + w_interface * plane[x].interface + w_gas * plane[x].gas +
                          w_grain * plane[x].grains;
                total += cost[x];
            }
            const sabo::parallel::SlabPartition equal(planes, ranks, 2);
            const auto balanced = sabo::parallel::SlabPartition::balanced(cost, ranks, 2);
            // the slowest rank's boundary traffic: two neighbours, the grains within 1.2 d of each face
            // (d/Δx = 4 on the coarse lattice: 5 planes' worth)
            double worst_comm = 0;
            for (int r = 0; r < ranks; ++r) {
                double bytes = 0, msgs = 0;
                for (const int face : {balanced.begin(r), balanced.end(r)}) {
                    if (face == 0 || face == planes) continue;
                    double ghosts = 0;
                    for (int x = std::max(0, face - 5 * refine); x < std::min(planes, face + 5 * refine); ++x)
                        ghosts += plane[x].grains;
                    bytes += 2 * halo_bytes_per_cell * boundary_cells + ghost_grain_bytes * ghosts;
                    msgs += messages_per_neighbour + 2;
                }
                worst_comm = std::max(worst_comm, msgs * latency_s + bytes / bandwidth_B_s);
                halo = std::max(halo, bytes);
            }
            // t1: one core's time; each rank's work goes rank_speed times faster than one core's
            const double t1 = total * interior_seconds;
            const double cores = static_cast<double>(ranks) * threads;
            const double comp_bal = balanced.imbalance(cost) * t1 / (ranks * rank_speed);
            const double t_eq = equal.imbalance(cost) * t1 / (ranks * rank_speed) + worst_comm;
            imb_eq += equal.imbalance(cost);
            imb_bal += balanced.imbalance(cost);
            comp += comp_bal;
            comm += worst_comm;
            eff_eq += t1 / (cores * t_eq);
            eff_bal += t1 / (cores * (comp_bal + worst_comm));
            eff_overlap += t1 / (cores * std::max(comp_bal, worst_comm));
        }
        const double n = static_cast<double>(frames.size());
        fmt::print("{:>6} {:>10.2f} {:>10.2f} {:>12.3f} {:>12.2f} {:>12.3f} {:>10.2f} {:>10.2f} {:>12.2f}\n",
                   ranks, imb_eq / n, imb_bal / n, 1e3 * comp / n, halo / 1e6, 1e3 * comm / n, eff_eq / n,
                   eff_bal / n, eff_overlap / n);
    }
    return 0;
}
