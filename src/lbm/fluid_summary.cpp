// SPDX-License-Identifier: MIT
#include "lbm/fluid_summary.h"

#include <algorithm>

namespace sabo::lbm {

FluidSummary summarize(const FluidFields& l, const std::function<std::uint8_t(int, int, int)>& region) {
    FluidSummary out;
    out.first_x = l.first_x;
    out.nz = l.nz;
    out.totals = l.totals;
    out.interface_cells = l.interface_cells;
    out.clamps = l.clamps;
    out.drained = l.drained;
    out.region_inflow = l.region_inflow;
    for (int z = 0; z < l.nz; ++z)
        for (int y = 0; y < l.ny; ++y)
            for (int x = 0; x < l.nx; ++x) {
                const std::size_t k = l.cell(x, y, z);
                if (!l.wet(k)) continue;
                if (l.fill[k] >= 0.1) {
                    out.front_x = std::max(out.front_x, x);
                    out.top_z = z;
                }
                if (l.covered[k] != 0) continue;
                const double m = l.fill[k] * l.density[k];
                out.free_mass += m;
                const std::uint8_t bits = region ? region(x, y, z) : 0;
                if ((bits & region_downstream) != 0) out.region_mass += m;
            }
    return out;
}

}  // namespace sabo::lbm
