#pragma once
// Phantom objects in an object map, judged against the simulator's truth: objects outside the
// room, floating above the floor, or moving fast while nothing real near them moves. A map that
// believes velocities only while it observes them, and objects only where they stand, has none.
#include <vector>

#include "makeway/common/object_estimate.hpp"
#include "makeway/sim/scene.hpp"
#include "makeway/sim/scene_dynamics.hpp"

namespace makeway::eval {

struct MapSanityParams {
    double max_floor_gap_m = 0.3;  ///< a box bottom higher than this above the floor (z = 0) floats
    double max_speed_mps =
        0.5;  ///< faster than this is a phantom unless something is pushed nearby
    double pushed_radius_m = 1.0;    ///< a true object this close that moved ...
    double pushed_speed_mps = 0.05;  ///< ... at least this fast ...
    std::vector<double> pushed_lookback_s{0.0, 0.5, 1.0,
                                          1.5};  ///< ... at any of these times before
};

struct MapSanity {
    std::size_t object_frames = 0;  ///< map objects checked, summed over frames
    std::size_t outside_room = 0;   ///< centre outside the room's floor
    std::size_t above_floor = 0;    ///< bottom more than max_floor_gap_m above the floor
    std::size_t fast_unpushed = 0;  ///< faster than max_speed_mps with nothing pushed nearby
    double max_speed_mps = 0.0, max_bottom_m = 0.0;
    std::size_t violations() const { return outside_room + above_floor + fast_unpushed; }
    void add(const MapSanity& o);
};

/// One frame of a map at t_s. `models` is sim::models_of(scene).
MapSanity check_map(const std::vector<ObjectEstimate>& objects, const sim::Scene& scene,
                    const std::vector<sim::ObjectModel>& models, double t_s,
                    const MapSanityParams& params = {});

}  // namespace makeway::eval
