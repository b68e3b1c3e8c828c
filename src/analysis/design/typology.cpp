// SPDX-License-Identifier: MIT
#include "analysis/design/typology.h"

#include <algorithm>

namespace sabo::analysis::design {

std::string opening_type(const Opening& o, std::size_t openings, double barrier_height) {
    if (o.reaches_crest) return o.height >= slit_aspect * o.width ? "slit" : "sectional";
    const double n_o = std::min(o.height, o.width);
    if (openings >= static_cast<std::size_t>(lattice_openings) && n_o <= lattice_size_ratio * barrier_height)
        return "lattice";
    return "slot";
}

std::string barrier_typology(std::span<const Opening> openings, double barrier_height) {
    if (openings.empty()) return "closed";
    const std::string first = opening_type(openings.front(), openings.size(), barrier_height);
    const bool alike = std::all_of(openings.begin(), openings.end(), [&](const Opening& o) {
        return opening_type(o, openings.size(), barrier_height) == first;
    });
    return alike ? first : "compound";
}

}  // namespace sabo::analysis::design
