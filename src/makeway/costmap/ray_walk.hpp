#pragma once
// The cells a ray crosses on a grid, as the obstacle layer clears them: the 8-connected Bresenham
// line from its start cell to its end cell, the end excluded. In closed form the cell at step t
// along the major axis has the minor coordinate round-half-up(t * minor / major) (the midpoint
// rule; Zingl's error-term loop visits the very same cells), so the walk can jump: where the caller
// says a block of cells holds nothing to visit, it goes straight to the first cell of the line
// outside that block. Most of a sweep's rays cross free space near the sensor, which is then
// crossed a block at a time.
#include <algorithm>
#include <cstdint>
#include <cstdlib>

namespace makeway::costmap {

inline int floor_div(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

/// a / b for 0 <= a, 0 < b: in 32 bits where a fits (a 64-bit division costs several times more,
/// and a costmap's rays are short).
inline std::int64_t quotient(std::int64_t a, int b) {
    return a <= INT32_MAX ? static_cast<std::int64_t>(static_cast<std::uint32_t>(a) /
                                                      static_cast<std::uint32_t>(b))
                          : a / b;
}

/// Calls visit(x, y) for every cell of the line from (x0, y0) to (x1, y1), the end excluded, in
/// order, except in blocks (block x block cells, aligned on multiples of `block`) for which
/// empty_block(bx, by) is true: those are crossed without a call. empty_block is asked once per
/// block the line enters, as it enters.
template <class EmptyBlock, class Visit>
void walk_ray(int x0, int y0, int x1, int y1, int block, EmptyBlock&& empty_block, Visit&& visit) {
    const int dx = std::abs(x1 - x0), dy = std::abs(y1 - y0);
    const bool x_major = dx >= dy;
    const int major = x_major ? dx : dy, minor = x_major ? dy : dx;
    const int p0 = x_major ? x0 : y0,
              q0 = x_major ? y0 : x0;  // starts along the major and minor axes
    const int sp = (x_major ? x1 >= x0 : y1 >= y0) ? 1 : -1,
              sq = (x_major ? y1 >= y0 : x1 >= x0) ? 1 : -1;
    // m(t) = floor(n / (2 major)) with n = 2 minor t + major, kept as quotient and remainder so a
    // step costs no division; a jump recomputes them once.
    const int two_major = 2 * major, two_minor = 2 * minor;
    int t = 0, m = 0, r = major;
    while (t < major) {
        const int p = p0 + sp * t, q = q0 + sq * m;
        const int bp = floor_div(p, block), bq = floor_div(q, block);
        // The first step whose cell leaves this block: along the major axis, or along the minor
        // one (the smallest t whose minor coordinate has moved `need` cells). In 64 bits: 2 major
        // need overflows int for rays longer than about 32,000 cells.
        const std::int64_t t_major =
            sp > 0 ? (std::int64_t{bp} + 1) * block - p0 : p0 - (std::int64_t{bp} * block - 1);
        std::int64_t t_minor = major;
        if (minor > 0) {
            const std::int64_t need =
                sq > 0 ? (std::int64_t{bq} + 1) * block - q0 : q0 - (std::int64_t{bq} * block - 1);
            t_minor = quotient(std::int64_t{two_major} * need - major + two_minor - 1, two_minor);
        }
        const int exit = static_cast<int>(std::min<std::int64_t>(
            major, std::max<std::int64_t>(t + 1, std::min(t_major, t_minor))));
        if (!empty_block(x_major ? bp : bq, x_major ? bq : bp)) {
            // Every cell up to the exit lies in this block: visited without asking again.
            for (; t < exit; ++t) {
                const int pc = p0 + sp * t, qc = q0 + sq * m;
                visit(x_major ? pc : qc, x_major ? qc : pc);
                r += two_minor;
                if (r >= two_major) r -= two_major, ++m;
            }
            continue;
        }
        t = exit;
        const std::int64_t n = std::int64_t{two_minor} * t + major;
        m = static_cast<int>(quotient(n, two_major));
        r = static_cast<int>(n - std::int64_t{m} * two_major);
    }
}

}  // namespace makeway::costmap
