// SPDX-License-Identifier: MIT
// The type of an open barrier from the dimensions of its openings, after the classification of
// Wehrmann, Hübl & Holzinger (2006) — with the thresholds as docs/design.md reads them: each opening of
// width S and height h_o (l_o = max, n_o = min) in a barrier of height h_bar is
//   slit       reaching the crest, tall: h_o ≥ 2 S;
//   sectional  reaching the crest, wide: h_o < 2 S;
//   slot       closed above (h_o < h_bar), one of few;
//   lattice    closed above, one of many small ones (4 or more, n_o ≤ h_bar/4): a grid;
// and a barrier whose openings are of different types is "compound"; one without openings "closed".
#pragma once
#include <span>
#include <string>

namespace sabo::analysis::design {

struct Opening {
    double width = 0.0;  // S, m
    double height =
        0.0;  // h_o, m (from its sill up; reaching the crest: the barrier's height above the sill)
    bool reaches_crest = true;
};
inline constexpr double slit_aspect = 2.0;  // h_o/S at and above which an opening to the crest is a slit
inline constexpr int lattice_openings = 4;  // closed openings from which the barrier is a grid
inline constexpr double lattice_size_ratio = 0.25;  // ... when n_o ≤ this × h_bar

[[nodiscard]] std::string opening_type(const Opening& o, std::size_t openings, double barrier_height);
[[nodiscard]] std::string barrier_typology(std::span<const Opening> openings, double barrier_height);

}  // namespace sabo::analysis::design
