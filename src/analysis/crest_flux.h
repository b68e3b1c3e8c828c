// SPDX-License-Identifier: MIT
// The grains' mass flux across a barrier, split at its crest: what overtops it and what goes through its
// outlets. Measured as a gauge measures discharge, over a control slab rather than at a plane: the flux is
// Σ m (v·n) / t over the grains whose centre lies within the barrier's thickness t downstream of its upstream
// face (n the face's normal), so that its time integral counts a grain that crosses the whole slab once, one
// that enters and turns back not at all, and needs no memory of where each grain was.
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "dem/particles.h"
#include "scenario/barrier.h"

namespace sabo::analysis {

struct CrestFlux {
    double over = 0.0;     // kg/s, grains above the crest (Z > H_bar): overtopping
    double through = 0.0;  // kg/s, grains at or below it: through the outlets
};

// Over the grains `near` names (indices into `p`: crest_flux_candidates()); the grains it leaves out are
// outside the slab. Zero without a barrier.
[[nodiscard]] CrestFlux crest_flux(const dem::Particles& p, std::span<const std::uint32_t> near,
                                   const scenario::BarrierInfo& barrier);
// The first `count` grains of `p` whose centre lies within `margin` of the slab (along the face normal):
// those that can enter it before any grain has moved `margin` (a neighbour list's skin bounds that until its
// rebuild), ascending, into `near`.
void crest_flux_candidates(const dem::Particles& p, std::size_t count, const scenario::BarrierInfo& barrier,
                           double margin, std::vector<std::uint32_t>& near);

}  // namespace sabo::analysis
