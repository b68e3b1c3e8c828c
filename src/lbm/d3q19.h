// SPDX-License-Identifier: MIT
// The D3Q19 velocity set (docs/lbm.md): rest, the 6 faces, the 12 edges. c_s² = 1/3.
// Opposite directions are adjacent (odd/even pairs after the rest direction), so ī = i ± 1.
#pragma once
#include <array>

namespace sabo::lbm {

inline constexpr int Q = 19;

inline constexpr std::array<int, Q> cx{0, 1, -1, 0, 0, 0, 0, 1, -1, 1, -1, 1, -1, 1, -1, 0, 0, 0, 0};
inline constexpr std::array<int, Q> cy{0, 0, 0, 1, -1, 0, 0, 1, -1, -1, 1, 0, 0, 0, 0, 1, -1, 1, -1};
inline constexpr std::array<int, Q> cz{0, 0, 0, 0, 0, 1, -1, 0, 0, 0, 0, 1, -1, -1, 1, 1, -1, -1, 1};

inline constexpr std::array<double, Q> weight{1.0 / 3.0,  1.0 / 18.0, 1.0 / 18.0, 1.0 / 18.0, 1.0 / 18.0,
                                              1.0 / 18.0, 1.0 / 18.0, 1.0 / 36.0, 1.0 / 36.0, 1.0 / 36.0,
                                              1.0 / 36.0, 1.0 / 36.0, 1.0 / 36.0, 1.0 / 36.0, 1.0 / 36.0,
                                              1.0 / 36.0, 1.0 / 36.0, 1.0 / 36.0, 1.0 / 36.0};

// ī: the direction opposite to i
[[nodiscard]] constexpr int opposite(int i) {
    return i == 0 ? 0 : (i % 2 == 1 ? i + 1 : i - 1);
}

}  // namespace sabo::lbm
