// SPDX-License-Identifier: MIT
#include "analysis/crest_flux.h"

namespace sabo::analysis {

CrestFlux crest_flux(const dem::Particles& p, std::size_t count, const scenario::BarrierInfo& barrier) {
    CrestFlux flux;
    if (!barrier.present() || barrier.thickness <= 0.0) return flux;
    const Vec3 face{barrier.face_x, 0.0, 0.0};
    const Vec3& n = barrier.face_normal;
    for (std::size_t i = 0; i < count; ++i) {
        const double s = dot(p.x[i] - face, n);
        if (s < 0.0 || s >= barrier.thickness) continue;
        const double rate = p.m[i] * dot(p.v[i], n);
        (p.x[i].z > barrier.height ? flux.over : flux.through) += rate;
    }
    flux.over /= barrier.thickness;
    flux.through /= barrier.thickness;
    return flux;
}

}  // namespace sabo::analysis
