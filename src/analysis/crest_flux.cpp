// SPDX-License-Identifier: MIT
#include "analysis/crest_flux.h"

namespace sabo::analysis {

CrestFlux crest_flux(const dem::Particles& p, std::span<const std::uint32_t> near,
                     const scenario::BarrierInfo& barrier) {
    CrestFlux flux;
    if (!barrier.present() || barrier.thickness <= 0.0) return flux;
    for (const std::uint32_t i : near) {
        if (!barrier.in_slab(p.x[i])) continue;
        const double rate = p.m[i] * dot(p.v[i], barrier.face_normal);
        (p.x[i].z > barrier.height ? flux.over : flux.through) += rate;
    }
    flux.over /= barrier.thickness;
    flux.through /= barrier.thickness;
    return flux;
}

void crest_flux_candidates(const dem::Particles& p, std::size_t count, const scenario::BarrierInfo& barrier,
                           double margin, std::vector<std::uint32_t>& near) {
    near.clear();
    if (!barrier.present()) return;
    for (std::size_t i = 0; i < count; ++i) {
        const double s = barrier.depth_into(p.x[i]);
        if (s >= -margin && s < barrier.thickness + margin) near.push_back(static_cast<std::uint32_t>(i));
    }
}

}  // namespace sabo::analysis
