#pragma once
// The cell index of a coordinate: floor(v / size) as an integer, without a libm call (a generic
// x86-64 build calls floor for every one; grids and voxel keys ask it for every point). Clamped to
// +-2^62 cells, where the cast is defined: a finite point can lie up to 3e38 m away (a damaged or
// hostile cloud), and every such point then shares the edge cell.
#include <algorithm>
#include <cstdint>

namespace makeway {

inline std::int64_t floor_index(double v, double size) {
    const double q = std::clamp(v / size, -0x1p62, 0x1p62);
    const auto i = static_cast<std::int64_t>(q);  // truncation: one down for negatives
    return static_cast<double>(i) > q ? i - 1 : i;
}

}  // namespace makeway
