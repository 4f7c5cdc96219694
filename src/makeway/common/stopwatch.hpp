#pragma once

#include <chrono>

namespace makeway {

// The clock every stage timing reads: monotonic, so a wall-clock step (NTP) never makes a stage
// look negative or hours long.
using SteadyClock = std::chrono::steady_clock;

// Milliseconds elapsed since t0 on the steady clock.
inline double ms_since(SteadyClock::time_point t0) {
    return std::chrono::duration<double, std::milli>(SteadyClock::now() - t0).count();
}

}  // namespace makeway
