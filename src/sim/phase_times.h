// SPDX-License-Identifier: MIT
// Where a run's wall-clock time goes, phase by phase (summary.json's "timing" block and the log's last
// lines; docs/outputs.md): seconds this process spent in each, the phases disjoint, so that with "other"
// (set-up, progress lines, what no phase names) they add up to its wall time; and two parts of them that
// the solvers time themselves (PhaseParts).
#pragma once
#include <array>
#include <cstddef>
#include <string_view>

namespace sabo::sim {

enum class Phase {
    lattice,       // the lattice's steps (on a device: enqueuing them and the waits inside a step)
    grain_cells,   // a coupled step's grain cells: found and covered (on a device: the grains sent up)
    fluid_forces,  // the fluid's force on each grain, read back (on a device: waiting for the collision)
    grains,        // the DEM steps, with the observers that read every step's contact forces
    exchanges,     // a divided run's exchanges with the other ranks, waiting for them included
    observers,     // series rows, frames, gauges: what the observers read and write between steps
    checkpoints,   // writing checkpoints
};
inline constexpr std::size_t phase_count = 7;
inline constexpr std::array<std::string_view, phase_count> phase_names = {
    "lattice", "grain_cells", "fluid_forces", "grains", "exchanges", "observers", "checkpoints"};

// Parts of the phases above: of `lattice`, the free surface's passes (a CPU lattice's; not a slab's waits for
// the others' orphan mass, which are exchanges); of `grains`, the neighbour lists' builds; of `exchanges`
// (they add up to it), the lattice's (its ghost planes, the orphan mass and the forces summed over the
// ranks), the grains' (their halo, re-partitions, visitors and force sums) and the slab faces' moves (pricing
// the planes, moving them and their grains).
struct PhaseParts {
    double free_surface = 0.0, neighbour_lists = 0.0;
    double lattice_exchanges = 0.0, grain_exchanges = 0.0, face_moves = 0.0;
};

class PhaseTimes {
  public:
    void add(Phase phase, double seconds) { seconds_[index(phase)] += seconds; }
    void set(Phase phase, double seconds) { seconds_[index(phase)] = seconds; }
    [[nodiscard]] double operator[](Phase phase) const { return seconds_[index(phase)]; }
    PhaseParts parts;
    [[nodiscard]] double sum() const {
        double s = 0.0;
        for (const double t : seconds_) s += t;
        return s;
    }

  private:
    static std::size_t index(Phase phase) { return static_cast<std::size_t>(phase); }
    std::array<double, phase_count> seconds_{};
};

}  // namespace sabo::sim
